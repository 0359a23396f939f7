"""The counting progress bar of rfc sim, sched and dse: on a terminal only, unless hidden."""

from __future__ import annotations

from rfc.cli.progress import counting_bar, run_counted


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


def test_a_percent_bar_shows_its_tasks_share(monkeypatch, capsys):
    monkeypatch.setenv("FORCE_COLOR", "1")
    monkeypatch.delenv("TTY_COMPATIBLE", raising=False)
    with counting_bar("{task.description}", percent=True) as bar:
        task = bar.add_task("simulating", total=1.0)
        bar.advance(task, 0.25)
        bar.refresh()
    captured = capsys.readouterr()
    assert "simulating" in captured.err
    assert " 25%" in captured.err
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


def inverse(value: int) -> float:
    return 1 / value


def test_counted_jobs_return_in_order_with_their_failures_and_count_on_the_bar(monkeypatch, capsys):
    monkeypatch.setenv("FORCE_COLOR", "1")
    results, failures = run_counted(
        "inverting", inverse, [4, 0, 2], lambda v: f"v={v}", workers=1, address=None
    )
    assert results == [0.25, None, 0.5]
    assert [f.job for f in failures] == ["v=0"]
    assert "division by zero" in failures[0].error
    assert "3/3" in capsys.readouterr().err
