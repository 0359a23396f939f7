"""Publishers on a shared channel, vectorized: what drives a scheduler in tests and benchmarks.

Input i sends messages of `transfer[i]` beats. A message raises `tvalid` and holds it until its
last beat has moved (one beat per granted, ready cycle), with `tlast` on that last beat; then
the input stays idle for a gap before its next message. Gaps are either fixed (the DSE's F_i)
or drawn uniformly at random, so arrivals are random.
"""

from __future__ import annotations

import numpy as np

from rfc.lib.schedulers.model.tree import BoolArray, IntArray


class Publishers:
    """N publishers on R replicates.

    Args:
        transfer: int[R, N] beats per message.
        gap: int[R, N] fixed idle cycles after each message (None: random, see `max_gap`).
        max_gap: Random gaps are uniform in 0 … `max_gap` (used when `gap` is None).
        rng: Random generator for gaps (and the initial phases when random).
        release: int[R, N] cycle of each input's first message (default: random phases when
            gaps are random, else 0 — all released at cycle 0).
    """

    def __init__(
        self,
        transfer: IntArray,
        *,
        gap: IntArray | None = None,
        max_gap: int = 0,
        rng: np.random.Generator | None = None,
        release: IntArray | None = None,
    ) -> None:
        self.transfer = np.asarray(transfer, dtype=np.int32)
        self.batch, self.n = self.transfer.shape
        self._gap = None if gap is None else np.broadcast_to(gap, self.transfer.shape)
        self._max_gap = max_gap
        self._rng = rng or np.random.default_rng(0)
        self._rows = np.arange(self.batch)
        if release is None:
            release = (
                np.zeros(self.transfer.shape, dtype=np.int64)
                if gap is not None
                else self._random_gaps()
            )
        self.remaining = np.zeros_like(self.transfer)
        self.idle = np.asarray(release, dtype=np.int32).copy()
        self._start_due()

    def _random_gaps(self, shape: tuple[int, ...] | None = None) -> IntArray:
        return self._rng.integers(0, self._max_gap + 1, size=shape or self.transfer.shape)

    def _start_due(self) -> None:
        np.copyto(self.remaining, self.transfer, where=(self.remaining == 0) & (self.idle == 0))

    @property
    def request(self) -> BoolArray:
        """bool[R, N]: `tvalid`, high while a message has beats left."""
        return self.remaining > 0

    @property
    def last(self) -> BoolArray:
        """bool[R, N]: `tlast`, high on the last beat of a message."""
        on_last: BoolArray = self.remaining == 1  # numpy types == as Any
        return on_last

    def advance(self, grant: IntArray) -> BoolArray:
        """End the cycle: the granted input moves one beat; idle inputs count their gap down.

        Args:
            grant: int[R], the input whose beat moved (already masked by `ready`), or -1.

        Returns:
            bool[R]: replicates whose granted input sent its last beat this cycle.
        """
        rows = np.nonzero(grant >= 0)[0]
        moved = grant[rows]
        self.remaining[rows, moved] -= 1
        finished = rows[self.remaining[rows, moved] == 0]
        self.idle -= (self.remaining == 0) & (self.idle > 0)
        if finished.size:
            which = grant[finished]
            gaps = (
                self._random_gaps((finished.size,))
                if self._gap is None
                else self._gap[finished, which]
            )
            self.idle[finished, which] = gaps
        self._start_due()
        done = np.zeros(self.batch, dtype=bool)
        done[finished] = True
        return done
