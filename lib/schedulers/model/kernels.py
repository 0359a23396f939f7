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
from numba import njit

#: Algorithm codes of the compiled kernels (the order of `rfc.lib.schedulers.spec.Algorithm`).
LRU, NPFP, PFP, ROEDF, LOEDF, LST = range(6)


@njit(cache=True)
def reset_state(algorithm, inputs, base, owner, computing, timer, seen, key, registered):
    """Synchronous reset of one replicate: no holder, LRU ranks = indices, counters at 0."""
    for k in range(algorithm.shape[0]):
        owner[k] = -1
        computing[k] = False
        timer[k] = 0
        for i in range(inputs[k]):
            seen[base[k] + i] = False
            registered[base[k] + i] = False
            key[base[k] + i] = i if algorithm[k] == LRU else 0


@njit(cache=True)
def _least_modular(request, done, key, holder, bits, valid, tkey, index):
    """ROEDF's Set Grant: the hardware's balanced tree on a circle of 2^(bits+1) extended keys.

    Key i is ``(key[i] << 1) | 1``, minus one for the holder (the holder wins ties); a right
    operand replaces the left one only when strictly earlier on the circle. Exact while pending
    deadlines lie within half the circle of each other, and beyond that what the hardware does.
    """
    n = request.shape[0]
    width = 2
    while width < n:
        width *= 2
    for i in range(width):
        valid[i] = i < n and request[i] and i != done
        tkey[i] = ((key[i] << 1) | 1) - (1 if i == holder else 0) if i < n else 0
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
    return index[0] if valid[0] else -1


@njit(cache=True)
def _clock_countdown(keep_moving, request, grant, done, load, owner, seen, key):
    """LOEDF/LST edge: load arrivals, count pending ones down, pick the least next value.

    Set Grant compares the counters' *next* values (merged Compute Condition), lowest index on
    ties, and the holder keeps the grant on a tie. LST does not count the input moving a beat.
    """
    best = -1
    least = 0
    for i in range(request.shape[0]):
        asks = request[i]
        if asks and not seen[i]:
            key[i] = load[i]
        elif (asks or seen[i]) and key[i] > 0 and not (keep_moving and i == grant):
            key[i] -= 1
        seen[i] = (asks or seen[i]) and i != done
        if asks and i != done and (best < 0 or key[i] < least):
            best = i
            least = key[i]
    if best >= 0 and owner >= 0 and owner != done and request[owner] and key[owner] == least:
        best = owner
    return best


@njit(cache=True)
def _first(request, done):
    for i in range(request.shape[0]):
        if request[i] and i != done:
            return i
    return -1


@njit(cache=True)
def _least_rank(request, done, rank):
    best = -1
    for i in range(request.shape[0]):
        if request[i] and i != done and (best < 0 or rank[i] < rank[best]):
            best = i
    return best


@njit(cache=True)
def clock_node(k, algorithm, bits, request, last, grant, load, deadline, state, scratch):
    """One rising edge of node k, given its inputs' request/last and this cycle's grant.

    Args:
        k: The node.
        algorithm: Its algorithm code.
        bits: Its counter width.
        request: bool[n], its inputs' requests (a leaf's `tvalid`, or its children's offers).
        last: bool[n], its inputs' `tlast` (a child's: that of the input it offers).
        grant: The input granted this cycle (already masked by `ready`), or -1.
        load: int[n], the values its keys load on arrival.
        deadline: int[n], relative deadlines (ROEDF registers timer + D).
        state: (owner, computing, timer, seen, key, registered), the node's own slices for the
            per-input ones.
        scratch: (valid, key, index) arrays for ROEDF's tree, at least twice n long.
    """
    owner, computing, timer, seen, key, registered = state
    n = request.shape[0]
    held = owner[k]
    complete = grant >= 0 and last[grant]
    done = grant if complete else -1
    if algorithm in (LOEDF, LST):
        owner[k] = _clock_countdown(algorithm == LST, request, grant, done, load, held, seen, key)
        return
    pause = False
    loading = -1
    if algorithm == ROEDF:
        for i in range(n):
            if request[i] and not registered[i]:
                loading = i
                break
        pause = loading >= 0
    reselect = (computing[k] or complete or held < 0 or algorithm == PFP) and not pause
    chosen = held
    if reselect:
        if algorithm == LRU:
            chosen = _least_rank(request, done, key)
        elif algorithm == ROEDF:
            chosen = _least_modular(request, done, key, held, bits, *scratch)
        else:
            chosen = _first(request, done)
    if algorithm == LRU and reselect and chosen >= 0:
        rank = key[chosen]
        for i in range(n):
            if key[i] > rank:
                key[i] -= 1
        key[chosen] = n - 1
    if algorithm == ROEDF:
        mask = (1 << bits) - 1
        if loading >= 0:
            key[loading] = (timer[k] + deadline[loading]) & mask
            registered[loading] = True
        if complete:
            registered[grant] = False
        timer[k] = (timer[k] + 1) & mask
        if pause and complete:
            chosen = -1
        computing[k] = pause
    owner[k] = chosen


@njit(cache=True)
def tree_cycle(tree, load, deadline, state, request, last, ready, work, scratch):
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
    algorithm, inputs, base, leaf_start, parent, slot, child_of, bits = tree
    owner, computing, timer, seen, key, registered = state
    node_request, node_last, offer, offer_leaf, node_grant = work
    nodes = algorithm.shape[0]
    for k in range(nodes - 1, -1, -1):
        first, n, start = base[k], inputs[k], leaf_start[k]
        if start >= 0:
            asks, ends = request[start : start + n], last[start : start + n]
        else:
            asks, ends = node_request[first : first + n], node_last[first : first + n]
        held = owner[k]
        offered = held if held >= 0 and not computing[k] and asks[held] else -1
        offer[k] = offered
        if offered < 0:
            offer_leaf[k] = -1
        elif start >= 0:
            offer_leaf[k] = start + offered
        else:
            offer_leaf[k] = offer_leaf[child_of[first + offered]]
        up = parent[k]
        if up >= 0:
            node_request[base[up] + slot[k]] = offered >= 0
            node_last[base[up] + slot[k]] = offered >= 0 and ends[offered]
    for k in range(nodes):
        up = parent[k]
        accepts = ready if up < 0 else node_grant[up] == slot[k]
        node_grant[k] = offer[k] if accepts else -1
    for k in range(nodes):
        first, n, start = base[k], inputs[k], leaf_start[k]
        stop = first + n
        if start >= 0:
            asks, ends = request[start : start + n], last[start : start + n]
        else:
            asks, ends = node_request[first:stop], node_last[first:stop]
        node_state = (
            owner,
            computing,
            timer,
            seen[first:stop],
            key[first:stop],
            registered[first:stop],
        )
        clock_node(
            k,
            algorithm[k],
            bits[k],
            asks,
            ends,
            node_grant[k],
            load[first:stop],
            deadline[first:stop],
            node_state,
            scratch,
        )
    return offer_leaf[0] if node_grant[0] >= 0 else -1


@njit(cache=True)
def tree_offer(tree, state, request, work):
    """The input the scheduler offers the channel this cycle (before `ready`), without a clock."""
    algorithm, inputs, base, leaf_start, parent, slot, child_of = tree[:7]
    owner, computing = state[0], state[1]
    node_request, offer_leaf = work[0], work[3]
    for k in range(algorithm.shape[0] - 1, -1, -1):
        first, n, start = base[k], inputs[k], leaf_start[k]
        asks = request[start : start + n] if start >= 0 else node_request[first : first + n]
        held = owner[k]
        offered = held if held >= 0 and not computing[k] and asks[held] else -1
        if offered < 0:
            offer_leaf[k] = -1
        elif start >= 0:
            offer_leaf[k] = start + offered
        else:
            offer_leaf[k] = offer_leaf[child_of[first + offered]]
        if parent[k] >= 0:
            node_request[base[parent[k]] + slot[k]] = offered >= 0
    return offer_leaf[0]


def work_arrays(nodes: int, flat: int, widest: int) -> tuple[tuple, tuple]:
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


@njit(cache=True)
def step_batch(tree, load, deadline, state, request, last, ready, grant, work, scratch):
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


@njit(cache=True)
def offer_batch(tree, state, request, offered, work):
    """`tree_offer` on every replicate of a batch."""
    owner, computing, timer, seen, key, registered = state
    for r in range(request.shape[0]):
        offered[r] = tree_offer(
            tree,
            (owner[r], computing[r], timer[r], seen[r], key[r], registered[r]),
            request[r],
            work,
        )


@njit(cache=True)
def reset_batch(tree, state):
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
