"""The DSE's inner loop, compiled: traffic, the scheduler's cycle and the metrics, streamed.

Each replicate runs N publishers (docs/dse.md): all released at cycle 0, input i sends a
message of T_i beats (`tvalid` held until its last beat moves, one beat per granted cycle, with
`tlast` on the last), then stays idle F_i cycles before the next message arrives; its deadline
is D_i cycles after arrival. The scheduler is `rfc.lib.schedulers.model.kernels.tree_cycle` —
the very code the co-simulation tests hold equal to the hardware. Nothing per cycle is kept:
per-input counters are folded into one row of `METRICS` per replicate.

Definitions (cycles are 0-based; a message's arrival a is the cycle its request rises):
response time r = g - a with g the cycle of its first beat; lateness L = f - d with f the cycle
of its last beat and d = a + D; a preemption is counted for input i when a beat of another
input moves while i's message has moved some but not all of its beats.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt
from numba import njit

from rfc.lib.schedulers.model.jit import kernel
from rfc.lib.schedulers.model.kernels import (
    BoolArray,
    IntArray,
    Scratch,
    State,
    Structure,
    Work,
    reset_state,
    tree_cycle,
    work_arrays,
)
from rfc.lib.schedulers.model.tree import SchedulerTree

FloatArray = npt.NDArray[np.float64]

#: Columns of the per-replicate metrics row, in order.
METRICS = (
    "granted",  # inputs granted at least once
    "completed",  # inputs that completed at least one message
    "preemptions",  # mean over completing inputs of preemptions / completed messages
    "response",  # mean response time r = g - a over completed messages (cycles)
    "lateness",  # mean lateness L = f - d over completed messages (cycles)
    "max_lateness",  # largest lateness of a completed message (cycles)
    "utilization",  # cycles a requesting input was granted / simulated cycles
    "messages",  # completed messages
    "missed",  # share of due messages that missed their deadline (late or still pending)
)
COLUMN = {name: index for index, name in enumerate(METRICS)}


@njit(cache=True)
def simulate(
    tree: Structure,
    load: IntArray,
    node_deadline: IntArray,
    transfer: IntArray,
    gap: IntArray,
    deadline: IntArray,
    cycles: int,
    out: FloatArray,
    work: Work,
    scratch: Scratch,
) -> None:
    """Simulate every replicate for `cycles` cycles and write its metrics row into `out`.

    Args:
        tree: Structure tuple of the scheduler (`SchedulerTree.structure`).
        load: int[R, M] key loads; node_deadline: int[R, M] per flat input (the tree's).
        transfer: int[R, N] T_i; gap: int[R, N] F_i; deadline: int[R, N] D_i.
        cycles: Simulated cycles per replicate.
        out: float[R, len(METRICS)], filled.
        work, scratch: `work_arrays` of the tree.
    """
    n = transfer.shape[1]
    nodes, flat = tree[0].shape[0], tree[6].shape[0]
    state = (
        np.empty(nodes, dtype=np.int64),
        np.empty(nodes, dtype=np.bool_),
        np.empty(nodes, dtype=np.int64),
        np.empty(flat, dtype=np.bool_),
        np.empty(flat, dtype=np.int64),
        np.empty(flat, dtype=np.bool_),
    )
    signals = (np.empty(n, dtype=np.bool_), np.empty(n, dtype=np.bool_))
    counters = np.empty((7, n), dtype=np.int64)
    wheel = np.empty(gap.max() + 2, dtype=np.int64)
    for r in range(transfer.shape[0]):
        _replicate(
            tree,
            (load[r], node_deadline[r]),
            (transfer[r], gap[r], deadline[r]),
            cycles,
            out[r],
            state,
            signals,
            counters,
            wheel,
            work,
            scratch,
        )


@kernel
def _replicate(
    tree: Structure,
    keys: tuple[IntArray, IntArray],
    traffic: tuple[IntArray, IntArray, IntArray],
    cycles: int,
    out: FloatArray,
    state: State,
    signals: tuple[BoolArray, BoolArray],
    counters: IntArray,
    wheel: IntArray,
    work: Work,
    scratch: Scratch,
) -> None:
    """One replicate of `simulate`, no allocation here: the arrays after `out` are its scratch.

    `keys` are the replicate's rows of `load` and `node_deadline`; `traffic` its rows of
    `transfer`, `gap` and `deadline`.
    """
    load, node_deadline = keys
    transfer, gap, deadline = traffic
    owner, computing, timer, seen, key, registered = state
    request, last = signals
    n = transfer.shape[0]
    remaining, arrival, first_beat = counters[0], counters[1], counters[2]
    beats, completions, preemptions, following = counters[3], counters[4], counters[5], counters[6]
    wheel_size = wheel.shape[0]
    reset_state(tree[0], tree[1], tree[2], owner, computing, timer, seen, key, registered)
    wheel[:] = -1
    for i in range(n):
        request[i] = False
        last[i] = False
        beats[i] = 0
        completions[i] = 0
        preemptions[i] = 0
        following[i] = wheel[0]
        wheel[0] = i
    current = -1
    response = 0
    lateness = 0
    worst = -(1 << 62)
    late = 0
    for t in range(cycles):
        slot = t % wheel_size
        i = wheel[slot]
        wheel[slot] = -1
        while i >= 0:
            remaining[i] = transfer[i]
            request[i] = True
            last[i] = remaining[i] == 1
            arrival[i] = t
            first_beat[i] = -1
            i = following[i]
        g = tree_cycle(tree, load, node_deadline, state, request, last, True, work, scratch)
        if g < 0:
            continue
        if current >= 0 and current != g and 0 < remaining[current] < transfer[current]:
            preemptions[current] += 1
        current = g
        beats[g] += 1
        if first_beat[g] < 0:
            first_beat[g] = t
        remaining[g] -= 1
        last[g] = remaining[g] == 1
        if remaining[g] == 0:
            request[g] = False
            completions[g] += 1
            response += first_beat[g] - arrival[g]
            overdue = t - (arrival[g] + deadline[g])
            lateness += overdue
            worst = max(worst, overdue)
            late += overdue > 0
            slot = (t + gap[g] + 1) % wheel_size
            following[g] = wheel[slot]
            wheel[slot] = g
    messages = 0
    pending_late = 0
    ratio = 0.0
    completing = 0
    granted = 0
    moved = 0
    for i in range(n):
        messages += completions[i]
        moved += beats[i]
        granted += beats[i] > 0
        if request[i] and arrival[i] + deadline[i] < cycles:
            pending_late += 1
        if completions[i] > 0:
            completing += 1
            ratio += preemptions[i] / completions[i]
    due = messages + pending_late
    out[0] = granted
    out[1] = completing
    out[2] = ratio / completing if completing else np.nan
    out[3] = response / messages if messages else np.nan
    out[4] = lateness / messages if messages else np.nan
    out[5] = worst if messages else np.nan
    out[6] = moved / cycles
    out[7] = messages
    out[8] = (late + pending_late) / due if due else 0.0


def run_replicates(
    tree: SchedulerTree, transfer: IntArray, gap: IntArray, deadline: IntArray, cycles: int
) -> FloatArray:
    """float[R, len(METRICS)]: the metrics of each replicate (see `simulate`)."""
    work, scratch = work_arrays(len(tree.algorithm), len(tree.child_of), int(tree.inputs.max()))
    out = np.empty((transfer.shape[0], len(METRICS)), dtype=np.float64)
    simulate(
        tree.structure,
        tree.load(),
        tree.node_deadline,
        np.ascontiguousarray(transfer, dtype=np.int64),
        np.ascontiguousarray(gap, dtype=np.int64),
        np.ascontiguousarray(deadline, dtype=np.int64),
        cycles,
        out,
        work,
        scratch,
    )
    return out


def compiled() -> bool:
    """Whether numba's disk cache holds the kernel, so that a new process loads, not compiles it.

    Always true with ``NUMBA_DISABLE_JIT=1`` (plain Python, nothing to compile).
    """
    stats = getattr(simulate, "stats", None)
    if stats is None:
        return True
    module = simulate.__module__.rpartition(".")[2]
    return any(Path(stats.cache_path).glob(f"{module}.{simulate.py_func.__name__}-*.nbi"))
