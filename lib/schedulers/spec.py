"""What a scheduler is at generation time: its algorithm, its inputs and their timing constants.

A `SchedulerSpec` fixes everything the hardware needs before it exists: the number of inputs N,
each input's transfer time T_i (beats) and relative deadline D_i (cycles), and the width of the
deadline/slack counters. A `CompositionSpec` is a scheduler whose inputs are schedulers (paper
§7.2.5). Both are frozen values so that generation is a pure function of them.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum

from rfc.errors import RfcError, did_you_mean

#: Smallest and largest number of inputs a generated scheduler accepts.
MIN_INPUTS = 1
MAX_INPUTS = 1024

#: Default timing when none is given: the means of the DSE's "large" dataset (docs/dse.md).
DEFAULT_TRANSFER = 100
DEFAULT_IDLE = 100

#: Extra counter bits beyond the largest timing constant: the lateness (or, for ROEDF, the
#: spread of pending deadlines) up to which the counters stay exact, about 128 x max(D, T).
COUNTER_HEADROOM_BITS = 8
#: The widest deadline/slack counters the generator builds.
MAX_COUNTER_BITS = 48
#: The longest deadline (cycles) or transfer (beats) that counters of the default width time.
MAX_TIMING = (1 << (MAX_COUNTER_BITS - 1 - COUNTER_HEADROOM_BITS)) - 1


class Algorithm(StrEnum):
    """The six scheduling algorithms of the paper (§6)."""

    LRU = "LRU"
    NPFP = "NPFP"
    PFP = "PFP"
    ROEDF = "ROEDF"
    LOEDF = "LOEDF"
    LST = "LST"

    @property
    def preemptive(self) -> bool:
        """Whether a holder may lose the grant before its `tlast`."""
        return self in (Algorithm.PFP, Algorithm.ROEDF, Algorithm.LOEDF, Algorithm.LST)

    @property
    def timed(self) -> bool:
        """Whether the algorithm uses the deadline (and slack) counters."""
        return self in (Algorithm.ROEDF, Algorithm.LOEDF, Algorithm.LST)

    @property
    def description(self) -> str:
        """One line for tables and help texts."""
        return _DESCRIPTIONS[self]


_DESCRIPTIONS = {
    Algorithm.LRU: "least recently used, non-preemptive",
    Algorithm.NPFP: "fixed priority (lower index wins), non-preemptive",
    Algorithm.PFP: "fixed priority (lower index wins), preemptive",
    Algorithm.ROEDF: "earliest deadline first, resource-optimized (pauses to recompute)",
    Algorithm.LOEDF: "earliest deadline first, latency-optimized",
    Algorithm.LST: "least slack time, preemptive",
}


def parse_algorithm(name: str | Algorithm) -> Algorithm:
    """Return the algorithm called `name` (any letter case).

    Raises:
        RfcError: No algorithm has that name; the closest names are suggested.
    """
    if isinstance(name, Algorithm):
        return name
    for algorithm in Algorithm:
        if algorithm.value.lower() == name.strip().lower():
            return algorithm
    names = [a.value for a in Algorithm]
    raise RfcError(
        f"unknown scheduling algorithm '{name}'; expected one of {', '.join(names)}",
        hint=did_you_mean(name.upper(), names),
    )


def default_counter_bits(transfer: Sequence[int], deadline: Sequence[int]) -> int:
    """Width of the deadline/slack counters: the largest constant plus `COUNTER_HEADROOM_BITS`."""
    largest = max(max(transfer, default=1), max(deadline, default=1))
    return largest.bit_length() + 1 + COUNTER_HEADROOM_BITS


def check_inputs(n: int, what: str = "a scheduler") -> None:
    """Reject an input count the generator cannot build.

    Raises:
        RfcError: `n` is outside `MIN_INPUTS` … `MAX_INPUTS`.
    """
    if not MIN_INPUTS <= n <= MAX_INPUTS:
        raise RfcError(
            f"{what} needs between {MIN_INPUTS} and {MAX_INPUTS} inputs, not {n}",
            hint="the paper evaluates N = 2 … 256",
        )


def check_timing(transfer: int, deadline: int) -> None:
    """Reject a deadline or transfer longer than the widest counters time with their headroom.

    Raises:
        RfcError: `transfer` or `deadline` is above `MAX_TIMING`.
    """
    if max(transfer, deadline) > MAX_TIMING:
        raise RfcError(
            f"a deadline of {deadline} cycles with a transfer of {transfer} beats is too long "
            f"for the scheduler's {MAX_COUNTER_BITS}-bit counters: they time at most "
            f"{MAX_TIMING} cycles",
            hint=f"give a deadline (or period) of at most {MAX_TIMING} cycles",
        )


def counter_bits_for(
    transfer: Sequence[int], deadline: Sequence[int], bits: int | None = None
) -> int:
    """The width of the deadline/slack counters: `bits` checked, else the default width.

    Raises:
        RfcError: `bits` is too narrow, or the constants too long for any counter.
    """
    if bits is None:
        check_timing(max(transfer), max(deadline))
        bits = default_counter_bits(transfer, deadline)
    check_counter_bits(bits, transfer, deadline)
    return bits


def check_counter_bits(bits: int, transfer: Sequence[int], deadline: Sequence[int]) -> None:
    """Reject counters too narrow to hold every constant with room for lateness.

    The counters are biased by H = 2^(bits-1): they must hold D_i + T_i below H.

    Raises:
        RfcError: `bits` is too small (or absurdly large).
    """
    needed = max(t + d for t, d in zip(transfer, deadline, strict=True)) + 1
    if not 1 <= bits <= MAX_COUNTER_BITS or (1 << (bits - 1)) < needed:
        raise RfcError(
            f"counter width {bits} bits cannot hold deadlines up to {max(deadline)} cycles and "
            f"transfers up to {max(transfer)} beats; it must be from 1 to {MAX_COUNTER_BITS} "
            f"and 2^(bits-1) must be at least {needed}",
            hint=f"leave it out to get {default_counter_bits(transfer, deadline)} bits",
        )


def _per_input(value: int | Sequence[int], n: int, name: str) -> tuple[int, ...]:
    values = (int(value),) * n if isinstance(value, int) else tuple(int(v) for v in value)
    if len(values) != n:
        raise RfcError(f"{name} has {len(values)} values for {n} inputs; give one per input")
    if min(values) < 1:
        raise RfcError(f"{name} must be at least 1 cycle for every input, got {min(values)}")
    return values


@dataclass(frozen=True)
class SchedulerSpec:
    """One scheduler: algorithm, N inputs, and the timing constants baked into its hardware.

    Attributes:
        algorithm: Which of the six.
        n: Number of inputs (publishers sharing the channel).
        transfer: T_i, beats of one message of input i (LST's initial slack is D_i - T_i).
        deadline: D_i, relative deadline of input i in cycles (implicit: T_i + F_i).
        counter_bits: Width of the deadline/slack counters (ROEDF, LOEDF, LST).
    """

    algorithm: Algorithm
    n: int
    transfer: tuple[int, ...]
    deadline: tuple[int, ...]
    counter_bits: int

    @classmethod
    def create(
        cls,
        algorithm: str | Algorithm,
        n: int,
        transfer: int | Sequence[int] = DEFAULT_TRANSFER,
        deadline: int | Sequence[int] | None = None,
        counter_bits: int | None = None,
    ) -> SchedulerSpec:
        """Validate and build a spec; scalars apply to every input.

        Args:
            algorithm: Algorithm or its name.
            n: Number of inputs.
            transfer: T_i in beats (one value or one per input).
            deadline: D_i in cycles; by default T_i + `DEFAULT_IDLE` (implicit deadline).
            counter_bits: Counter width; by default `default_counter_bits`.

        Raises:
            RfcError: Any value is out of range.
        """
        check_inputs(n)
        transfers = _per_input(transfer, n, "the transfer time")
        if deadline is None:
            deadline = [t + DEFAULT_IDLE for t in transfers]
        deadlines = _per_input(deadline, n, "the deadline")
        bits = counter_bits_for(transfers, deadlines, counter_bits)
        return cls(parse_algorithm(algorithm), n, transfers, deadlines, bits)

    @property
    def name(self) -> str:
        """A short readable name, such as ``LOEDF16``."""
        return f"{self.algorithm.value}{self.n}"


@dataclass(frozen=True)
class CompositionSpec:
    """A scheduler whose inputs are schedulers: `parent` arbitrates between `children`.

    The composite has the inputs of its children side by side (child 0's first). The parent
    sees one input per child: it requests while the child offers a grant, and its `tlast` is
    the offered input's. The parent's own timing constants per child are the child's largest
    transfer and smallest deadline, so a timed parent treats each child as its most urgent input.

    Attributes:
        parent: The arbitrating scheduler (n = number of children).
        children: The schedulers (or compositions) whose inputs the composite has.
    """

    parent: SchedulerSpec
    children: tuple[SchedulerSpec | CompositionSpec, ...]

    @classmethod
    def create(
        cls,
        parent: str | Algorithm,
        children: Sequence[SchedulerSpec | CompositionSpec],
        counter_bits: int | None = None,
    ) -> CompositionSpec:
        """Compose `children` under a `parent` algorithm.

        Raises:
            RfcError: Fewer than two children, or a bad parent.
        """
        if len(children) < 2:
            raise RfcError(f"a composition needs at least two schedulers, got {len(children)}")
        transfer = [max(child.transfer) for child in children]
        deadline = [min(child.deadline) for child in children]
        spec = SchedulerSpec.create(parent, len(children), transfer, deadline, counter_bits)
        composite = cls(spec, tuple(children))
        check_inputs(composite.n, "a composition")
        return composite

    @property
    def n(self) -> int:
        """Number of inputs of the composite: the children's, side by side."""
        return sum(child.n for child in self.children)

    @property
    def transfer(self) -> tuple[int, ...]:
        """T_i of every input of the composite."""
        return tuple(t for child in self.children for t in child.transfer)

    @property
    def deadline(self) -> tuple[int, ...]:
        """D_i of every input of the composite."""
        return tuple(d for child in self.children for d in child.deadline)

    @property
    def offsets(self) -> tuple[int, ...]:
        """Index of each child's first input in the composite."""
        starts, total = [], 0
        for child in self.children:
            starts.append(total)
            total += child.n
        return tuple(starts)

    @property
    def name(self) -> str:
        """A readable name, such as ``LRU(LOEDF128,LST128)``."""
        return f"{self.parent.algorithm.value}({','.join(c.name for c in self.children)})"


AnySchedulerSpec = SchedulerSpec | CompositionSpec


def parse_scheduler(
    text: str,
    n: int,
    transfer: int | Sequence[int] = DEFAULT_TRANSFER,
    deadline: int | Sequence[int] | None = None,
    counter_bits: int | None = None,
) -> AnySchedulerSpec:
    """A spec from a name: an algorithm (``LOEDF``) or a composition (``LRU(LOEDF,LST)``).

    A composition's children share the `n` inputs in order, as evenly as possible, unless
    sizes are given (``LRU(LOEDF:100,LST:28)``); children may be compositions themselves.

    Raises:
        RfcError: The text is not an algorithm or a well-formed composition of them.
    """
    check_inputs(n)
    transfers = _per_input(transfer, n, "the transfer time")
    deadlines = None if deadline is None else _per_input(deadline, n, "the deadline")
    return _parse(text.replace(" ", ""), n, transfers, deadlines, counter_bits, text)


def _parse(text: str, n: int, transfers: tuple[int, ...], deadlines: tuple[int, ...] | None,
           bits: int | None, whole: str) -> AnySchedulerSpec:  # fmt: skip
    if "(" not in text:
        return SchedulerSpec.create(text, n, transfers, deadlines, bits)
    head, _, rest = text.partition("(")
    if not rest.endswith(")"):
        raise RfcError(
            f"cannot read the composition '{whole}': a '(' is not closed",
            hint="write it like LRU(LOEDF,LST) or LRU(LOEDF:128,LST:128)",
        )
    parts = [_sized(part) for part in _split_children(rest[:-1], whole)]
    names = [name for name, _ in parts]
    left = n - sum(size for _, size in parts if size is not None)
    unsized = sum(size is None for _, size in parts)
    # The inputs left over go to the unsized children evenly, the last ones taking one more.
    shares = iter(
        left // unsized + (1 if rank >= unsized - left % unsized else 0) for rank in range(unsized)
    )
    sizes = [next(shares) if size is None else size for _, size in parts]
    if min(sizes) < 1 or sum(sizes) != n:
        raise RfcError(
            f"the children of '{whole}' must share the {n} inputs, at least one each; "
            f"the sizes given add up to {n - left}",
            hint="give sizes that add up to N, or leave some out to share the rest",
        )
    children, start = [], 0
    for name, size in zip(names, sizes, strict=True):
        stop = start + size
        kid_deadlines = None if deadlines is None else deadlines[start:stop]
        children.append(_parse(name, size, transfers[start:stop], kid_deadlines, bits, whole))
        start = stop
    return CompositionSpec.create(head, children, bits)


_SIZED = re.compile(r"(.+?)(?::(\d+))?")


def _sized(part: str) -> tuple[str, int | None]:
    """A child's name and the size given after a colon, if any (`part` is not empty)."""
    match = _SIZED.fullmatch(part)
    assert match is not None, "every non-empty text matches"
    return match.group(1), int(match.group(2)) if match.group(2) else None


def _split_children(text: str, whole: str) -> list[str]:
    parts, depth, current = [], 0, ""
    for char in text:
        depth += {"(": 1, ")": -1}.get(char, 0)
        if char == "," and depth == 0:
            parts.append(current)
            current = ""
        else:
            current += char
    parts.append(current)
    if depth != 0 or any(not part for part in parts):
        raise RfcError(
            f"cannot read the composition '{whole}'", hint="write it like LRU(LOEDF,LST)"
        )
    return parts
