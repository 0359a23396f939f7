"""Figures: drawn on worker processes, the files are the bytes one process writes."""

from __future__ import annotations

from rfc.dse.plots import FIGURES, write_figures
from rfc.dse.sweep import Plan, run_sweep


def test_figures_drawn_on_two_processes_equal_one_process(tmp_path):
    result = run_sweep(Plan(datasets=("cc1",), sizes=(2, 4), replicates=2), 1, synthesis=False)
    (tmp_path / "one").mkdir()
    (tmp_path / "two").mkdir()
    assert write_figures(result, tmp_path / "one", jobs=1) == list(FIGURES)
    write_figures(result, tmp_path / "two", jobs=2)
    files = sorted(p.name for p in (tmp_path / "one").iterdir())
    assert files == sorted(f"{name}.{kind}" for name in FIGURES for kind in ("png", "svg"))
    for name in files:
        assert (tmp_path / "two" / name).read_bytes() == (tmp_path / "one" / name).read_bytes()
