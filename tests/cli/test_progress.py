"""The counting progress bar of rfc sim and rfc sched: on a terminal only, unless hidden."""

from __future__ import annotations

from rfc.cli.progress import counting_bar


def run_a_bar(hidden: bool = False) -> None:
    with counting_bar("replaying", hidden=hidden) as bar:
        task = bar.add_task("replay", total=3)
        for _ in range(3):
            bar.advance(task)


def test_the_bar_counts_on_stderr_at_a_terminal(monkeypatch, capsys):
    monkeypatch.setenv("FORCE_COLOR", "1")
    monkeypatch.delenv("TTY_COMPATIBLE", raising=False)
    run_a_bar()
    captured = capsys.readouterr()
    assert "replaying" in captured.err
    assert "3/3" in captured.err
    assert captured.out == ""


def test_the_bar_stays_off_a_pipe(monkeypatch, capsys):
    monkeypatch.delenv("FORCE_COLOR", raising=False)
    monkeypatch.setenv("TTY_COMPATIBLE", "0")
    run_a_bar()
    assert capsys.readouterr() == ("", "")


def test_a_hidden_bar_stays_off_a_terminal(monkeypatch, capsys):
    monkeypatch.setenv("FORCE_COLOR", "1")
    run_a_bar(hidden=True)
    assert capsys.readouterr() == ("", "")
