"""The paper's Figures 6-14 and Table 3 from a sweep, as PNG and SVG (matplotlib, no display).

Figures 7-10 show the main dataset (``large`` when simulated, else the first one), Figures
11-13 one panel per corner case simulated (the main dataset when none was), Figure 14 the
combined schedulers at the largest N. Lines carry the 95 % confidence interval as error bars.
"""

from __future__ import annotations

import textwrap
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from functools import partial
from multiprocessing import get_context
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from rfc.dse.captions import CAPTIONS
from rfc.dse.sweep import ALGORITHMS, COMBINATIONS, SweepResult
from rfc.dse.tables import table3

_MARKERS = dict(zip(ALGORITHMS, "osD^vx", strict=True))


def main_dataset(result: SweepResult) -> str:
    """The dataset of Figures 7-10 and 14."""
    return "large" if "large" in result.plan.datasets else result.plan.datasets[0]


def corner_datasets(result: SweepResult) -> list[str]:
    """The datasets of Figures 11-13."""
    corners = [name for name in result.plan.datasets if name.startswith("cc")]
    return corners or [main_dataset(result)]


def _lines(axis: Axes, result: SweepResult, name: str, metric: str, label: str) -> None:
    for algorithm in ALGORITHMS:
        found = (result.point(name, algorithm, n) for n in result.plan.sizes)
        points = [p for p in found if p is not None]
        summaries = [p.summary(metric) for p in points]
        axis.errorbar(
            [p.n for p in points],
            [s.mean for s in summaries],
            yerr=[s.ci95 for s in summaries],
            marker=_MARKERS[algorithm],
            markersize=4,
            capsize=2,
            label=algorithm,
        )
    axis.set_xscale("log", base=2)
    axis.set_xticks(result.plan.sizes, [str(n) for n in result.plan.sizes])
    axis.set_xlabel("accelerators N")
    axis.set_ylabel(label)
    axis.grid(True, alpha=0.3)


def _figure(panels: int, columns: int = 2) -> tuple[Figure, list[Axes]]:
    rows = (panels + columns - 1) // columns
    width = 5.2 * min(panels, columns)
    figure, axes = plt.subplots(rows, min(panels, columns), figsize=(width, 3.8 * rows))
    flat = list(axes.flat) if hasattr(axes, "flat") else [axes]
    for axis in flat[panels:]:
        axis.set_visible(False)
    return figure, flat[:panels]


def _metric_figure(result: SweepResult, metric: str, label: str) -> Figure:
    figure, (axis,) = _figure(1)
    _lines(axis, result, main_dataset(result), metric, label)
    axis.set_title(f"{main_dataset(result)} dataset")
    axis.legend(fontsize=8)
    return figure


def figure6(result: SweepResult) -> Figure:
    """LUT and FF versus N."""
    figure, axes = _figure(2)
    for axis, field in zip(axes, ("lut", "ff"), strict=True):
        for algorithm in ALGORITHMS:
            rows = sorted(
                (r.n, getattr(r, field)) for r in result.resources if r.algorithm == algorithm
            )
            axis.plot(
                [n for n, _ in rows],
                [v for _, v in rows],
                marker=_MARKERS[algorithm],
                label=algorithm,
            )
        axis.set_xlabel("accelerators N")
        axis.set_ylabel(field.upper())
        axis.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    if not result.resources:
        axes[0].set_title("synthesis skipped (--no-synth)")
    return figure


def figure8(result: SweepResult) -> Figure:
    """Grouped bars: completed (full) and granted-only (hatched) accelerators per N."""
    figure, (axis,) = _figure(1)
    name = main_dataset(result)
    width = 0.8 / len(ALGORITHMS)
    for index, algorithm in enumerate(ALGORITHMS):
        xs, done, only = [], [], []
        for position, n in enumerate(result.plan.sizes):
            point = result.point(name, algorithm, n)
            if point is None:
                continue
            completed = point.summary("completed").mean
            xs.append(position + (index - len(ALGORITHMS) / 2 + 0.5) * width)
            done.append(completed)
            only.append(point.summary("granted").mean - completed)
        color = f"C{index}"
        axis.bar(xs, done, width, color=color, label=algorithm)
        axis.bar(xs, only, width, bottom=done, color="white", edgecolor=color, hatch="////")
    axis.set_xticks(range(len(result.plan.sizes)), [str(n) for n in result.plan.sizes])
    axis.set_xlabel("accelerators N")
    axis.set_ylabel("accelerators")
    axis.set_ylim(0, 1.08 * max(result.plan.sizes))
    axis.set_title(f"{name} dataset")
    axis.legend(fontsize=8)
    return figure


def _corner_figure(result: SweepResult, metric: str, label: str) -> Figure:
    names = corner_datasets(result)
    figure, axes = _figure(len(names))
    for axis, name in zip(axes, names, strict=True):
        _lines(axis, result, name, metric, label)
        axis.set_title(name)
    axes[0].legend(fontsize=8)
    return figure


def figure14(result: SweepResult) -> Figure:
    """Accelerators granted (and completed) with LOEDF, LST and their combinations under LRU."""
    figure, (axis,) = _figure(1)
    name = main_dataset(result)
    n = max(result.plan.sizes)
    names = ["LOEDF", "LST", *COMBINATIONS]
    found = ((s, result.point(name, s, n)) for s in names)
    shown = [(s, p) for s, p in found if p is not None]
    granted = [p.summary("granted") for _, p in shown]
    completed = [p.summary("completed") for _, p in shown]
    positions = range(len(shown))
    axis.bar(positions, [s.mean for s in granted], 0.6, yerr=[s.ci95 for s in granted],
             color="white", edgecolor="C0", hatch="////", capsize=3, label="granted")  # fmt: skip
    axis.bar(positions, [s.mean for s in completed], 0.6, yerr=[s.ci95 for s in completed],
             color="C0", capsize=3, label="completed")  # fmt: skip
    axis.set_xticks(list(positions), [s for s, _ in shown], rotation=20, fontsize=8)
    axis.set_ylabel("accelerators")
    axis.set_title(f"{name} dataset, N = {n}")
    axis.legend(fontsize=8)
    return figure


def table3_figure(result: SweepResult) -> Figure:
    """Table 3 rendered as a figure."""
    figure, (axis,) = _figure(1)
    rows = table3(result.resources)
    axis.axis("off")
    if rows:
        cells = [[str(r["n"]), f"{r['lut_ratio']:.2f}", f"{r['ff_ratio']:.2f}"] for r in rows]
        table = axis.table(cellText=cells, colLabels=["N", "LUTs", "FFs"], loc="center")
        table.scale(1, 1.4)
    else:
        axis.text(0.5, 0.5, "synthesis skipped (--no-synth)", ha="center")
    axis.set_title("ROEDF / LOEDF")
    return figure


def _response_and_lateness(result: SweepResult) -> Figure:
    figure, axes = _figure(2)
    name = main_dataset(result)
    _lines(axes[0], result, name, "response", "(a) response time (cycles)")
    _lines(axes[1], result, name, "lateness", "(b) lateness (cycles)")
    axes[0].legend(fontsize=8)
    return figure


FIGURES: dict[str, Callable[[SweepResult], Figure]] = {
    "figure6": figure6,
    "figure7": lambda r: _metric_figure(r, "preemptions", "preemptions per transaction"),
    "figure8": figure8,
    "figure9": lambda r: _metric_figure(r, "utilization", "channel utilization U"),
    "figure10": _response_and_lateness,
    "figure11": lambda r: _corner_figure(r, "preemptions", "preemptions per transaction"),
    "figure12": lambda r: _corner_figure(r, "response", "response time (cycles)"),
    "figure13": lambda r: _corner_figure(r, "lateness", "lateness (cycles)"),
    "figure14": figure14,
    "table3": table3_figure,
}


def write_figures(result: SweepResult, directory: Path, jobs: int = 1) -> list[str]:
    """Save every figure as PNG and SVG into `directory`; return their base names.

    With `jobs` > 1 the figures are drawn in that many forked processes (drawing text is most of
    a small sweep's time; forked workers have matplotlib imported already).
    """
    names = list(FIGURES)
    write = partial(_write_figure, result, directory)
    if jobs > 1:
        with ProcessPoolExecutor(min(jobs, len(names)), mp_context=get_context("fork")) as pool:
            list(pool.map(write, names))
    else:
        for name in names:
            write(name)
    return names


def _write_figure(result: SweepResult, directory: Path, name: str) -> None:
    plt.rcParams["svg.hashsalt"] = "rfc-dse"
    figure = FIGURES[name](result)
    figure.suptitle(textwrap.fill(CAPTIONS[name], 80), fontsize=10)
    figure.tight_layout()
    figure.savefig(directory / f"{name}.png", dpi=110, metadata={"Software": None})
    figure.savefig(directory / f"{name}.svg", metadata={"Date": None})
    plt.close(figure)
