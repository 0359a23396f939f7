"""The paper's metrics measured on a recorded channel: an oracle independent of the kernel.

Given per-cycle `tvalid` (request), `tlast` (last) and the grant of a run, `measure` derives
every metric of `rfc.dse.kernel.METRICS` from the signals alone, with the same definitions
(docs/dse.md). `--verify-hdl` applies it to the grants of the generated hardware in GHDL, and
the tests to the model, and compare with what the DSE kernel reported.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from rfc.dse.kernel import METRICS


def measure(
    request: npt.NDArray[np.bool_],
    last: npt.NDArray[np.bool_],
    grant: npt.NDArray[np.int64],
    deadline: npt.ArrayLike,
) -> npt.NDArray[np.float64]:
    """float[len(METRICS)]: the metrics of one run.

    Args:
        request: bool[C, N], `tvalid` of every input on every cycle.
        last: bool[C, N], `tlast`.
        grant: int[C], the input granted on each cycle (-1: none); a beat moves when granted.
        deadline: int[N], relative deadline D_i of each input.
    """
    cycles, n = request.shape
    deadlines = np.asarray(deadline, dtype=np.int64)
    arrival = [-1] * n
    first_beat = [-1] * n
    moved = [0] * n
    beats = np.zeros(n, dtype=np.int64)
    completions = np.zeros(n, dtype=np.int64)
    preemptions = np.zeros(n, dtype=np.int64)
    responses, latenesses = [], []
    ended = [True] * n  # the previous message ended (or none began): a high request arrives
    current = -1
    for t in range(cycles):
        for i in np.nonzero(request[t])[0]:
            if ended[i]:
                arrival[i], first_beat[i], moved[i], ended[i] = t, -1, 0, False
        g = int(grant[t])
        if g < 0:
            continue
        if current >= 0 and current != g and moved[current] > 0 and not ended[current]:
            preemptions[current] += 1
        current = g
        beats[g] += 1
        moved[g] += 1
        if first_beat[g] < 0:
            first_beat[g] = t
        if last[t, g]:
            completions[g] += 1
            responses.append(first_beat[g] - arrival[g])
            latenesses.append(t - arrival[g] - int(deadlines[g]))
            ended[g] = True
    pending_late = sum(1 for i in range(n) if not ended[i] and arrival[i] + deadlines[i] < cycles)
    messages = int(completions.sum())
    completing = completions > 0
    late = sum(1 for value in latenesses if value > 0)
    due = messages + pending_late
    # Sums in input order, as the kernel adds them, so that equal runs give equal bits.
    ratio = 0.0
    for i in np.nonzero(completing)[0]:
        ratio += int(preemptions[i]) / int(completions[i])
    row = {
        "granted": float((beats > 0).sum()),
        "completed": float(completing.sum()),
        "preemptions": ratio / int(completing.sum()) if completing.any() else math.nan,
        "response": sum(responses) / messages if responses else math.nan,
        "lateness": sum(latenesses) / messages if latenesses else math.nan,
        "max_lateness": float(max(latenesses)) if latenesses else math.nan,
        "utilization": float(beats.sum()) / cycles,
        "messages": float(messages),
        "missed": (late + pending_late) / due if due else 0.0,
    }
    return np.array([row[name] for name in METRICS])
