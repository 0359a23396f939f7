"""Every scheduler's clock cycle, compiled: the one implementation behind models, co-sim and DSE.

A scheduler is a tree of statechart *nodes* stored flat, in pre-order (a parent before its
children): a single algorithm is one node; a composition (paper §7.2.5) is a parent node whose
inputs are its children's offers. Per node k: ``algorithm[k]``, ``inputs[k]``, ``base[k]`` (its
first input in the flat per-input arrays), ``leaf_start[k]`` (its first scheduler input when it
is a leaf, else -1), ``parent[k]`` and ``slot[k]`` (its input index in the parent), ``bits[k]``;
per flat input, ``child_of`` (the node feeding it, or -1 at a leaf).

State of one replicate: per node ``owner``, ``computing`` and ``timer``; per flat input
``seen``, ``key`` (LRU rank, LOEDF/LST biased counter, ROEDF absolute deadline) and
``registered``. The register-transfer rules are those of docs/schedulers.md ("Cycle
semantics"); the co-simulation tests hold this code to the generated hardware cycle by cycle.

Every function is plain Python under ``NUMBA_DISABLE_JIT=1`` (for debugging); compiled, the
results are cached on disk so that a new process does not compile again.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from rfc.lib.schedulers.model.jit import kernel

#: Algorithm codes of the compiled kernels (the order of `rfc.lib.schedulers.spec.Algorithm`).
LRU, NPFP, PFP, ROEDF, LOEDF, LST = range(6)
#: A key larger than any counter (counters are at most 48 bits wide).
_NONE = 1 << 62

BoolArray = npt.NDArray[np.bool_]
IntArray = npt.NDArray[np.int64]
#: (algorithm, inputs, base, leaf_start, parent, slot, child_of, bits) of a tree.
Structure = tuple[IntArray, ...]
#: (owner, computing, timer, seen, key, registered): one replicate's, or a batch's (axis 0: R).
State = tuple[IntArray, BoolArray, IntArray, BoolArray, IntArray, BoolArray]
#: (node_request, node_last, offer, offer_leaf, node_grant): `tree_cycle`'s scratch arrays.
Work = tuple[BoolArray, BoolArray, IntArray, IntArray, IntArray]
#: (valid, key, index): the scratch arrays of ROEDF's comparison tree.
Scratch = tuple[BoolArray, IntArray, IntArray]


@kernel
def reset_state(
    algorithm: IntArray,
    inputs: IntArray,
    base: IntArray,
    owner: IntArray,
    computing: BoolArray,
    timer: IntArray,
    seen: BoolArray,
    key: IntArray,
    registered: BoolArray,
) -> None:
    """Synchronous reset of one replicate: no holder, LRU ranks = indices, counters at 0."""
    for k in range(algorithm.shape[0]):
        owner[k] = -1
        computing[k] = False
        timer[k] = 0
        for i in range(inputs[k]):
            seen[base[k] + i] = False
            registered[base[k] + i] = False
            key[base[k] + i] = i if algorithm[k] == LRU else 0


@kernel
def _least_modular(
    n: int,
    request: BoolArray,
    at: int,
    done: int,
    key: IntArray,
    base: int,
    holder: int,
    bits: int,
    scratch: Scratch,
) -> int:
    """ROEDF's Set Grant: the hardware's balanced tree on a circle of 2^(bits+1) extended keys.

    Key i is ``(key[i] << 1) | 1``, minus one for the holder (the holder wins ties); a right
    operand replaces the left one only when strictly earlier on the circle. Exact while pending
    deadlines lie within half the circle of each other, and beyond that what the hardware does.
    """
    valid, tkey, index = scratch
    width = 2
    while width < n:
        width *= 2
    for i in range(width):
        valid[i] = i < n and request[at + i] and i != done
        tkey[i] = ((key[base + i] << 1) | 1) - (1 if i == holder else 0) if i < n else 0
        index[i] = i
    mask = (1 << (bits + 1)) - 1
    half = 1 << bits
    while width > 1:
        width //= 2
        for j in range(width):
            left, right = 2 * j, 2 * j + 1
            take_right = valid[right] and (
                not valid[left] or ((tkey[right] - tkey[left]) & mask) >= half
            )
            valid[j] = valid[left] or valid[right]
            if take_right:
                tkey[j] = tkey[right]
                index[j] = index[right]
            else:
                tkey[j] = tkey[left]
                index[j] = index[left]
    least: int = index[0] if valid[0] else -1
    return least


@kernel
def _clock_countdown(
    keep_moving: bool,
    n: int,
    request: BoolArray,
    at: int,
    grant: int,
    done: int,
    load: IntArray,
    base: int,
    holder: int,
    seen: BoolArray,
    key: IntArray,
) -> int:
    """LOEDF/LST edge: load arrivals, count pending ones down, pick the least next value.

    Set Grant compares the counters' *next* values (merged Compute Condition), lowest index on
    ties, and the holder keeps the grant on a tie. LST does not count the input moving a beat.
    Written as three branch-free passes (update, least value, first index) so that they
    vectorize.
    """
    frozen = grant if keep_moving else -1
    asking, arrived = request[at : at + n], seen[base : base + n]
    keys, loads = key[base : base + n], load[base : base + n]
    for i in range(n):
        asks = asking[i]
        pending = asks | arrived[i]
        counting = pending & (keys[i] > 0) & (i != frozen)
        keys[i] = loads[i] if asks and not arrived[i] else keys[i] - counting
        arrived[i] = pending & (i != done)
    least = _NONE
    for i in range(n):
        least = min(least, keys[i] if asking[i] and i != done else _NONE)
    if least == _NONE:
        return -1
    if holder >= 0 and holder != done and asking[holder] and keys[holder] == least:
        return holder
    for i in range(n):
        if asking[i] and i != done and keys[i] == least:
            return i
    return -1


@kernel
def _first(n: int, request: BoolArray, at: int, done: int) -> int:
    for i in range(n):
        if request[at + i] and i != done:
            return i
    return -1


@kernel
def _least_rank(n: int, request: BoolArray, at: int, done: int, rank: IntArray, base: int) -> int:
    best = -1
    least = 0
    for i in range(n):
        if request[at + i] and i != done and (best < 0 or rank[base + i] < least):
            best = i
            least = rank[base + i]
    return best


@kernel
def clock_node(
    k: int,
    tree: Structure,
    request: BoolArray,
    last: BoolArray,
    at: int,
    grant: int,
    load: IntArray,
    deadline: IntArray,
    state: State,
    scratch: Scratch,
) -> None:
    """One rising edge of node k, given its inputs' request/last and this cycle's grant.

    Args:
        k: The node.
        tree: The structure tuple (see `tree_cycle`).
        request: bool array holding the node's inputs' requests from index `at` (a leaf's
            `tvalid`, or its children's offers).
        last: bool array holding their `tlast` from `at` (a child's: that of its offer).
        at: Index of the node's first input in `request` and `last`.
        grant: The input granted this cycle (already masked by `ready`), or -1.
        load: int[M], the values keys load on arrival.
        deadline: int[M], relative deadlines (ROEDF registers timer + D).
        state: (owner, computing, timer, seen, key, registered) of the replicate.
        scratch: (valid, key, index) arrays for ROEDF's tree, at least twice n long.
    """
    owner, seen, key = state[0], state[3], state[4]
    algorithm, n, base, bits = tree[0][k], tree[1][k], tree[2][k], tree[7][k]
    held = owner[k]
    complete = grant >= 0 and last[at + grant]
    done = grant if complete else -1
    if algorithm in (LOEDF, LST):
        owner[k] = _clock_countdown(
            algorithm == LST, n, request, at, grant, done, load, base, held, seen, key
        )
    elif algorithm == ROEDF:
        owner[k] = _clock_roedf(
            k, n, base, bits, request, at, grant, done, held, deadline, state, scratch
        )
    elif complete or held < 0 or algorithm == PFP:
        owner[k] = _reselect(algorithm == LRU, n, base, request, at, done, key)


@kernel
def _reselect(
    lru: bool, n: int, base: int, request: BoolArray, at: int, done: int, key: IntArray
) -> int:
    """Set Grant of LRU and fixed priority; LRU moves the new holder to the bottom."""
    if not lru:
        return _first(n, request, at, done)
    chosen = _least_rank(n, request, at, done, key, base)
    if chosen >= 0:
        rank = key[base + chosen]
        for i in range(base, base + n):
            if key[i] > rank:
                key[i] -= 1
        key[base + chosen] = n - 1
    return chosen


@kernel
def _clock_roedf(
    k: int,
    n: int,
    base: int,
    bits: int,
    request: BoolArray,
    at: int,
    grant: int,
    done: int,
    held: int,
    deadline: IntArray,
    state: State,
    scratch: Scratch,
) -> int:
    """ROEDF edge: register one waiting request per cycle (pausing), then Set Grant."""
    computing, timer, key, registered = state[1], state[2], state[4], state[5]
    loading = -1
    for i in range(n):
        if request[at + i] and not registered[base + i]:
            loading = i
            break
    pause = loading >= 0
    chosen = held
    if (computing[k] or done >= 0 or held < 0) and not pause:
        chosen = _least_modular(n, request, at, done, key, base, held, bits, scratch)
    mask = (1 << bits) - 1
    if pause:
        key[base + loading] = (timer[k] + deadline[base + loading]) & mask
        registered[base + loading] = True
    if done >= 0:
        registered[base + grant] = False
    timer[k] = (timer[k] + 1) & mask
    computing[k] = pause
    return -1 if pause and done >= 0 else chosen


@kernel
def _offer(
    k: int,
    tree: Structure,
    owner: IntArray,
    computing: BoolArray,
    signals: BoolArray,
    at: int,
    offer_leaf: IntArray,
) -> int:
    """Node k's offer (its holder when that input requests, outside a pause) and its leaf."""
    held: int = owner[k]
    if held < 0 or computing[k] or not signals[at + held]:
        offer_leaf[k] = -1
        return -1
    start = tree[3][k]
    offer_leaf[k] = start + held if start >= 0 else offer_leaf[tree[6][tree[2][k] + held]]
    return held


@kernel
def tree_cycle(
    tree: Structure,
    load: IntArray,
    deadline: IntArray,
    state: State,
    request: BoolArray,
    last: BoolArray,
    ready: bool,
    work: Work,
    scratch: Scratch,
) -> int:
    """One clock cycle of a scheduler tree on one replicate; returns this cycle's grant.

    Bottom-up, every node offers the channel to its holder when that input requests (outside a
    ROEDF pause); a parent sees child c requesting while c offers, with the offered input's
    `tlast`. Top-down, the root's offer is granted when `ready`, and a child's `ready` is its
    parent's grant of it. Then every node takes its clock edge.

    Args:
        tree: (algorithm, inputs, base, leaf_start, parent, slot, child_of, bits) int arrays.
        load: int[M], per flat input, the value its key loads on arrival.
        deadline: int[M], per flat input, the relative deadline.
        state: (owner, computing, timer, seen, key, registered) of this replicate.
        request: bool[N], the scheduler inputs' `tvalid`.
        last: bool[N], their `tlast`.
        ready: The channel accepts a beat this cycle.
        work: (node_request, node_last, offer, offer_leaf, node_grant) scratch arrays.
        scratch: ROEDF tree scratch (see `clock_node`).

    Returns:
        The scheduler input granted on this cycle, or -1.
    """
    owner, computing = state[0], state[1]
    node_request, node_last, offer, offer_leaf, node_grant = work
    base, leaf_start, parent, slot = tree[2], tree[3], tree[4], tree[5]
    nodes = base.shape[0]
    if nodes == 1:
        offered = _offer(0, tree, owner, computing, request, 0, offer_leaf)
        granted = offered if ready else -1
        clock_node(0, tree, request, last, 0, granted, load, deadline, state, scratch)
        return granted
    for k in range(nodes - 1, -1, -1):
        leaf = leaf_start[k] >= 0
        at = leaf_start[k] if leaf else base[k]
        offered = _offer(
            k, tree, owner, computing, request if leaf else node_request, at, offer_leaf
        )
        offer[k] = offered
        up = parent[k]
        if up >= 0:
            ends = last if leaf else node_last
            node_request[base[up] + slot[k]] = offered >= 0
            node_last[base[up] + slot[k]] = offered >= 0 and ends[at + offered]
    for k in range(nodes):
        up = parent[k]
        accepts = ready if up < 0 else node_grant[up] == slot[k]
        node_grant[k] = offer[k] if accepts else -1
    for k in range(nodes):
        if leaf_start[k] >= 0:
            clock_node(
                k, tree, request, last, leaf_start[k], node_grant[k], load, deadline, state, scratch
            )
        else:
            clock_node(
                k,
                tree,
                node_request,
                node_last,
                base[k],
                node_grant[k],
                load,
                deadline,
                state,
                scratch,
            )
    granted_leaf: int = offer_leaf[0] if node_grant[0] >= 0 else -1
    return granted_leaf


@kernel
def tree_offer(tree: Structure, state: State, request: BoolArray, work: Work) -> int:
    """The input the scheduler offers the channel this cycle (before `ready`), without a clock."""
    owner, computing = state[0], state[1]
    node_request, offer_leaf = work[0], work[3]
    base, leaf_start, parent, slot = tree[2], tree[3], tree[4], tree[5]
    for k in range(base.shape[0] - 1, -1, -1):
        leaf = leaf_start[k] >= 0
        at = leaf_start[k] if leaf else base[k]
        offered = _offer(
            k, tree, owner, computing, request if leaf else node_request, at, offer_leaf
        )
        if parent[k] >= 0:
            node_request[base[parent[k]] + slot[k]] = offered >= 0
    offered_leaf: int = offer_leaf[0]
    return offered_leaf


def work_arrays(nodes: int, flat: int, widest: int) -> tuple[Work, Scratch]:
    """Scratch arrays for `tree_cycle` and `tree_offer` of a tree of this size."""
    work = (
        np.zeros(flat, dtype=np.bool_),
        np.zeros(flat, dtype=np.bool_),
        np.full(nodes, -1, dtype=np.int64),
        np.full(nodes, -1, dtype=np.int64),
        np.full(nodes, -1, dtype=np.int64),
    )
    width = 2
    while width < widest:
        width *= 2
    scratch = (
        np.zeros(width, dtype=np.bool_),
        np.zeros(width, dtype=np.int64),
        np.zeros(width, dtype=np.int64),
    )
    return work, scratch


# `tree_cycle`'s arguments, for every replicate of the batch at once.
@kernel
def step_batch(
    tree: Structure,
    load: IntArray,
    deadline: IntArray,
    state: State,
    request: BoolArray,
    last: BoolArray,
    ready: BoolArray,
    grant: IntArray,
    work: Work,
    scratch: Scratch,
) -> None:
    """`tree_cycle` on every replicate r of a batch (state arrays have a leading R axis)."""
    owner, computing, timer, seen, key, registered = state
    for r in range(request.shape[0]):
        grant[r] = tree_cycle(
            tree,
            load[r],
            deadline[r],
            (owner[r], computing[r], timer[r], seen[r], key[r], registered[r]),
            request[r],
            last[r],
            ready[r],
            work,
            scratch,
        )


@kernel
def offer_batch(
    tree: Structure, state: State, request: BoolArray, offered: IntArray, work: Work
) -> None:
    """`tree_offer` on every replicate of a batch."""
    owner, computing, timer, seen, key, registered = state
    for r in range(request.shape[0]):
        offered[r] = tree_offer(
            tree,
            (owner[r], computing[r], timer[r], seen[r], key[r], registered[r]),
            request[r],
            work,
        )


@kernel
def reset_batch(tree: Structure, state: State) -> None:
    """`reset_state` on every replicate of a batch."""
    algorithm, inputs, base = tree[:3]
    owner, computing, timer, seen, key, registered = state
    for r in range(owner.shape[0]):
        reset_state(
            algorithm,
            inputs,
            base,
            owner[r],
            computing[r],
            timer[r],
            seen[r],
            key[r],
            registered[r],
        )
