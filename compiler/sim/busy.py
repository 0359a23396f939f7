"""The logic's ``busy`` bits in a simulated replay: never call it idle while it still works.

The generated top level has one ``busy`` bit per hardware accelerator and publisher
(`rfc.lower.system.busy`): high while the block has taken a message and not yet completed one
on each of its outputs, or while a message waits at its input. Every simulator path reads them
and counts the drain window only while all are low. A bit that stays high while no DMA transfer
completes for the cap (``--stall-cycles``) is given up on: the replay goes on as if the block
were idle and says so in a warning naming it. The bit is watched again once it falls.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class BusyWatch:
    """Read one replay's ``busy`` bits.

    Attributes:
        names: The block each bit watches, bit 0 first.
        cap: Cycles a bit may stay high without a completed DMA transfer.
        warnings: What was given up on, in words, in the order it happened.
    """

    names: tuple[str, ...]
    cap: int
    warnings: list[str] = field(default_factory=list)
    _since: int | None = field(default=None, init=False)
    _given_up: int = field(default=0, init=False)

    def completed(self, cycle: int) -> None:
        """A DMA transfer completed at `cycle`: the logic is moving."""
        if self._since is not None:
            self._since = cycle

    def busy(self, cycle: int, bits: int) -> bool:
        """Whether the logic still works at `cycle`, its ``busy`` port reading `bits`."""
        self._given_up &= bits
        working = bits & ~self._given_up
        if not working:
            self._since = None
            return False
        if self._since is None:
            self._since = cycle
        if cycle - self._since < self.cap:
            return True
        self._given_up |= working
        self._since = None
        blocks = ", ".join(f"'{n}'" for i, n in enumerate(self.names) if working >> i & 1)
        self.warnings.append(
            f"at cycle {cycle:,} the logic was still busy ({blocks}) after {self.cap:,} cycles "
            "without a DMA transfer: the replay went on without waiting for it, and any "
            "message it still owed is missing from the output; an accelerator that answers "
            "some inputs with no message does this, else raise --stall-cycles"
        )
        return False
