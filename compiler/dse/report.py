"""The HTML report of a sweep: parameters, every figure, and the metrics as tables.

A single self-contained page beside the figures it shows (``report.html`` links
``figureN.svg`` in the same directory); values are mean ± half-width of the 95 % interval.
"""

from __future__ import annotations

import html
import math

from rfc.dse.captions import CAPTIONS
from rfc.dse.datasets import dataset
from rfc.dse.kernel import METRICS
from rfc.dse.sweep import SweepResult
from rfc.dse.tables import table3

#: Metric column headings of the report's tables.
HEADINGS = {
    "granted": "granted",
    "completed": "completed",
    "preemptions": "preemptions / transaction",
    "response": "response time (cycles)",
    "lateness": "lateness (cycles)",
    "max_lateness": "max lateness (cycles)",
    "utilization": "utilization U",
    "messages": "completed messages",
    "missed": "missed deadlines",
}

_STYLE = """
body { font-family: sans-serif; max-width: 1100px; margin: 2em auto; color: #222; }
table { border-collapse: collapse; margin: 1em 0; font-size: 0.85em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.5em; text-align: right; }
th { background: #f0f0f0; } td.name { text-align: left; }
img { max-width: 100%; } figure { margin: 2em 0; }
"""


def _cell(mean: float, ci95: float) -> str:
    if math.isnan(mean):
        return "n/a"
    return f"{mean:.4g} ± {ci95:.2g}"


def _table(header: list[str], rows: list[list[str]], names: int = 1) -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = []
    for row in rows:
        cells = [
            f'<td class="name">{html.escape(v)}</td>' if i < names else f"<td>{html.escape(v)}</td>"
            for i, v in enumerate(row)
        ]
        body.append(f"<tr>{''.join(cells)}</tr>")
    return f"<table><tr>{head}</tr>{''.join(body)}</table>"


def render(result: SweepResult, figures: list[str]) -> str:
    """The report's HTML text."""
    parts = [
        "<!DOCTYPE html><html><head><meta charset='utf-8'>",
        "<title>rfc dse: scheduler design-space exploration</title>",
        f"<style>{_STYLE}</style></head><body>",
        "<h1>Scheduler design-space exploration</h1>",
        "<p>Paper §7.2; definitions in docs/dse.md. Values are the mean over "
        "replicates ± the half-width of the 95&nbsp;% confidence interval (Student's t).</p>",
    ]
    rows = []
    for name in result.plan.datasets:
        data = dataset(name)
        rows.append([data.label, f"{data.cycles}", f"{result.plan.replicates_of(data)}"])
    parts.append(_table(["dataset", "cycles", "replicates"], rows))
    parts.append(f"<p>N = {', '.join(map(str, result.plan.sizes))}; seed {result.plan.seed}.</p>")
    for name in figures:
        parts.append(
            f"<figure><img src='{name}.svg' alt='{html.escape(CAPTIONS[name])}'>"
            f"<figcaption>{html.escape(CAPTIONS[name])}</figcaption></figure>"
        )
    for name in result.plan.datasets:
        parts.append(f"<h2>Dataset {html.escape(name)}</h2>")
        rows = []
        for point in (p for p in result.points if p.dataset == name):
            cells = [point.scheduler, str(point.n)]
            for metric in METRICS:
                summary = point.summary(metric)
                cells.append(_cell(summary.mean, summary.ci95))
            rows.append(cells)
        parts.append(_table(["scheduler", "N", *(HEADINGS[m] for m in METRICS)], rows))
    if result.resources:
        parts.append("<h2>Resources (GHDL + Yosys synth_xilinx, xc7; T = 100, D = 200)</h2>")
        rows = [[r.algorithm, str(r.n), str(r.lut), str(r.ff)] for r in result.resources]
        parts.append(_table(["algorithm", "N", "LUT", "FF"], rows))
        rows = [
            [str(r["n"]), f"{r['lut_ratio']:.2f}", f"{r['ff_ratio']:.2f}"]
            for r in table3(result.resources)
        ]
        parts.append("<h2>Table 3: ROEDF / LOEDF</h2>")
        parts.append(_table(["N", "LUT ratio", "FF ratio"], rows))
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"
