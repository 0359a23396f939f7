"""The sweep as data: one JSON document, CSV tables, and the paper's Table 3.

`document` is what `rfc dse --json` prints and `results.json` holds: the datasets, every point
with every metric as mean and 95 % interval, the LUT/FF of each algorithm at each N, and
Table 3's ROEDF/LOEDF ratios.
"""

from __future__ import annotations

import csv
import io

from rfc.dse.datasets import CLOCK_MHZ, dataset
from rfc.dse.kernel import METRICS
from rfc.dse.sweep import Resources, SweepResult

#: Columns of results.csv: one row per point and metric.
RESULT_FIELDS = (
    "dataset", "scheduler", "n", "replicates", "cycles", "counter_bits",
    "metric", "mean", "ci95", "low", "high", "defined_in",
)  # fmt: skip


def table3(resources: tuple[Resources, ...]) -> list[dict[str, float | int]]:
    """ROEDF/LOEDF LUT and FF ratios per N (the paper's Table 3)."""
    by = {(r.algorithm, r.n): r for r in resources}
    rows = []
    for n in sorted({r.n for r in resources}):
        roedf, loedf = by.get(("ROEDF", n)), by.get(("LOEDF", n))
        if roedf and loedf:
            rows.append(
                {
                    "n": n,
                    "lut_ratio": round(roedf.lut / loedf.lut, 3),
                    "ff_ratio": round(roedf.ff / loedf.ff, 3),
                }
            )
    return rows


def document(result: SweepResult) -> dict[str, object]:
    """The whole sweep as one JSON-friendly document."""
    datasets = {}
    for name in result.plan.datasets:
        data = dataset(name)
        datasets[name] = {
            "transfer_mean": data.transfer_mean,
            "idle_mean": data.idle_mean,
            "sigma": data.sigma,
            "duration_us": data.duration_us,
            "clock_mhz": CLOCK_MHZ,
            "cycles": data.cycles,
            "replicates": result.plan.replicates_of(data),
        }
    return {
        "seed": result.plan.seed,
        "n": list(result.plan.sizes),
        "datasets": datasets,
        "metrics": list(METRICS),
        "points": [point.as_dict() for point in result.points],
        "resources": [
            {"algorithm": r.algorithm, "n": r.n, "lut": r.lut, "ff": r.ff} for r in result.resources
        ],
        "table3": table3(result.resources),
    }


def results_csv(result: SweepResult) -> str:
    """results.csv: one row per point and metric."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(RESULT_FIELDS)
    for point in result.points:
        for metric in METRICS:
            summary = point.summary(metric)
            writer.writerow(
                [
                    point.dataset, point.scheduler, point.n, point.replicates, point.cycles,
                    point.counter_bits, metric, _number(summary.mean), _number(summary.ci95),
                    _number(summary.low), _number(summary.high), summary.count,
                ]
            )  # fmt: skip
    return out.getvalue()


def resources_csv(result: SweepResult) -> str:
    """resources.csv: LUT and FF of each algorithm at each N."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(("algorithm", "n", "lut", "ff"))
    for r in result.resources:
        writer.writerow((r.algorithm, r.n, r.lut, r.ff))
    return out.getvalue()


def table3_markdown(result: SweepResult) -> str:
    """Table 3 as Markdown."""
    lines = [
        "# Table 3: resource-latency EDF trade-off (ROEDF / LOEDF)",
        "",
        "| N | LUT ratio | FF ratio |",
        "|---:|---:|---:|",
    ]
    lines += [
        f"| {r['n']} | {r['lut_ratio']:.2f} | {r['ff_ratio']:.2f} |"
        for r in table3(result.resources)
    ]
    return "\n".join(lines) + "\n"


def _number(value: float) -> str:
    return "" if value != value else f"{value:.6g}"
