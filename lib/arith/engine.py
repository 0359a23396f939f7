"""A resource-shared fixed-point engine: programs, their static schedule, and the bit-exact model.

A `Program` is a straight-line list of steps over a word memory: load an input, write a
constant, multiply-accumulate two words into a third, take the cosine and sine of a word, store
a word to the outputs. `ProgramBuilder` writes programs (a 4x4 transform product, forward
kinematics) and schedules them for the hardware in `rfc.lib.arith.engine_hdl`: one step per
cycle, one multiply-accumulate unit, and no-ops wherever a step would read a word before the
pipeline has written it, with the latencies of the hardware's pipelines (`Latencies`). `run`
computes what the hardware computes, bit for bit.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from enum import IntEnum
from typing import Any

import numpy as np

from rfc.lib.arith.mac import MAC_GUARD_BITS, multiply_accumulate
from rfc.lib.arith.mac_hdl import mac_stages
from rfc.lib.arith.sincos import SinCosConfig, sincos
from rfc.lib.fixed import FixedFormat, fixed_to_float, float_to_fixed
from rfc.lib.fixed.pipeline import FIXED_TO_FLOAT_STAGES, FLOAT_TO_FIXED_STAGES


class Op(IntEnum):
    """What a step does."""

    NOP = 0
    MAC = 1
    LOAD = 2
    CONST = 3
    SINCOS = 4
    PUT_COS = 5
    PUT_SIN = 6
    STORE = 7
    DONE = 8


@dataclass(frozen=True)
class Step:
    """One instruction.

    Attributes:
        op: The operation.
        a: First operand's address (MAC, SINCOS, STORE) or the constant's index (CONST).
        b: Second operand's address (MAC).
        dst: Address written (LOAD, CONST, PUT_COS, PUT_SIN, and MAC when `last`).
        first: This MAC starts a new sum.
        last: This MAC ends its sum, whose rounded value is written to `dst`.
    """

    op: Op
    a: int = 0
    b: int = 0
    dst: int = 0
    first: bool = False
    last: bool = False


@dataclass(frozen=True)
class Latencies:
    """Cycles from issuing a step to its effect: the registers of the engine's pipelines.

    Attributes:
        load: From a LOAD to the cycle its word is written (the float64 → fixed converter's
            registers; 0 for raw words).
        mac: From a sum's last product to the cycle the sum is written (`mac_stages`).
        store: From a STORE to the cycle its value enters the outputs (a read register and the
            fixed → float64 converter's registers; 0 for raw words).
    """

    load: int
    mac: int
    store: int


def latencies(fmt: FixedFormat, float_io: bool) -> Latencies:
    """The engine's latencies for words of `fmt`, with float64 inputs and outputs or raw ones."""
    return Latencies(
        load=FLOAT_TO_FIXED_STAGES if float_io else 0,
        mac=mac_stages(fmt),
        store=1 + FIXED_TO_FLOAT_STAGES if float_io else 0,
    )


@dataclass(frozen=True)
class Program:
    """A scheduled program and the engine it runs on.

    Attributes:
        steps: One per cycle (SINCOS waits for its result), ending with DONE.
        constants: Raw values the CONST steps write.
        size: Words of memory.
        inputs: Values a message brings (LOAD steps take them in order).
        outputs: Values a result holds (STORE steps give them in order).
        fmt: The words' fixed-point format.
        float_io: Inputs and outputs are float64 bit patterns (converted on LOAD and STORE,
            ties to even) rather than raw words.
        sincos: The sine/cosine unit's configuration, or None when the program needs none.
    """

    steps: tuple[Step, ...]
    constants: tuple[int, ...]
    size: int
    inputs: int
    outputs: int
    fmt: FixedFormat
    float_io: bool
    sincos: SinCosConfig | None

    @property
    def cycles(self) -> int:
        """Cycles from taking a message to offering its result.

        A step per cycle; each SINCOS also waits for the iterative unit (its latency, a cycle
        that registers the angle and a handshake cycle).
        """
        waits = sum(step.op == Op.SINCOS for step in self.steps)
        return len(self.steps) + waits * (self.sincos.iterative_latency + 2 if self.sincos else 0)


def wrap(raw: Any, width: int) -> Any:
    """The signed value of the low `width` bits of `raw` (what a narrower register keeps)."""
    half = 1 << (width - 1)
    return ((raw + half) & ((1 << width) - 1)) - half


def _exact(value: Any) -> Any:
    """An int, or a NumPy array as Python ints (products of words overflow int64)."""
    if isinstance(value, np.ndarray) and value.ndim:
        return value.astype(object)
    return int(value)


def run(program: Program, inputs: Sequence[Any]) -> list[Any]:
    """What the engine outputs for one message: the bit-exact model.

    Each input is an int, or a NumPy array of them to run a batch of messages at once (the
    outputs are then arrays too).

    Raises:
        ValueError: The number of inputs is not the program's.
    """
    if len(inputs) != program.inputs:
        raise ValueError(f"the program takes {program.inputs} inputs, not {len(inputs)}")
    fmt = program.fmt
    to_fixed = np.vectorize(lambda bits: float_to_fixed(int(bits), fmt).raw, otypes=[object])
    to_float = np.vectorize(lambda raw: fixed_to_float(int(raw), fmt), otypes=[object])
    memory: list[Any] = [0] * program.size
    pending = iter(inputs)
    outputs: list[Any] = []
    terms: list[tuple[Any, Any]] = []
    cos: Any = 0
    sin: Any = 0
    for step in program.steps:
        if step.op == Op.MAC:
            terms = [] if step.first else terms
            terms.append((memory[step.a], memory[step.b]))
            if step.last:
                memory[step.dst] = multiply_accumulate(terms, fmt)
        elif step.op == Op.LOAD:
            value = _exact(next(pending))
            memory[step.dst] = _exact(to_fixed(value)) if program.float_io else value
        elif step.op == Op.CONST:
            memory[step.dst] = program.constants[step.a]
        elif step.op == Op.SINCOS:
            assert program.sincos is not None
            angle = wrap(memory[step.a], program.sincos.angle_format.width)
            cos, sin = (_exact(v) for v in sincos(np.asarray(angle, np.int64), program.sincos))
        elif step.op in (Op.PUT_COS, Op.PUT_SIN):
            memory[step.dst] = cos if step.op == Op.PUT_COS else sin
        elif step.op == Op.STORE:
            word = memory[step.a]
            outputs.append(_exact(to_float(word)) if program.float_io else word)
    shapes = [np.shape(value) for value in inputs if np.ndim(value)]
    if shapes:
        # Outputs that are constants come out as ints: give them the batch's shape.
        outputs = [np.broadcast_to(np.asarray(v, dtype=object), shapes[0]) for v in outputs]
    return outputs


@dataclass
class ProgramBuilder:
    """Writes a program step by step, giving each new word its own address.

    Every word is written once, so the schedule only has to respect reads after writes.
    """

    fmt: FixedFormat
    float_io: bool = False
    sincos: SinCosConfig | None = None
    _steps: list[Step] = field(default_factory=list)
    _constants: dict[int, int] = field(default_factory=dict)
    _size: int = 0
    _inputs: int = 0
    _outputs: int = 0

    def _word(self) -> int:
        self._size += 1
        return self._size - 1

    def load(self) -> int:
        """The next input, as a new word."""
        self._inputs += 1
        word = self._word()
        self._steps.append(Step(Op.LOAD, dst=word))
        return word

    def constant(self, raw: int) -> int:
        """A word holding `raw` (one word per distinct value)."""
        if not self.fmt.min_raw <= raw <= self.fmt.max_raw:
            raise ValueError(f"constant {raw} lies outside {self.fmt}")
        if raw not in self._constants:
            self._constants[raw] = self._word()
            index = list(self._constants).index(raw)
            self._steps.append(Step(Op.CONST, a=index, dst=self._constants[raw]))
        return self._constants[raw]

    def dot(self, terms: list[tuple[int, int]]) -> int:
        """A new word: ``Σ a * b`` over pairs of addresses, rounded once."""
        if not 1 <= len(terms) <= 1 << MAC_GUARD_BITS:
            raise ValueError(f"a sum takes 1 to {1 << MAC_GUARD_BITS} products, not {len(terms)}")
        word = self._word()
        for i, (a, b) in enumerate(terms):
            last = i == len(terms) - 1
            self._steps.append(Step(Op.MAC, a, b, word if last else 0, i == 0, last))
        return word

    def cos_sin(self, angle: int) -> tuple[int, int]:
        """Two new words: the cosine and sine of the word at `angle` (radians)."""
        if self.sincos is None:
            raise ValueError("this builder has no sine/cosine unit")
        cos, sin = self._word(), self._word()
        self._steps += [Step(Op.SINCOS, a=angle), Step(Op.PUT_COS, dst=cos)]
        self._steps.append(Step(Op.PUT_SIN, dst=sin))
        return cos, sin

    def store(self, word: int) -> None:
        """Give the word at `word` as the next output."""
        self._outputs += 1
        self._steps.append(Step(Op.STORE, a=word))

    def build(self) -> Program:
        """The program, scheduled: no-ops where a step must wait, DONE at the end."""
        delays = latencies(self.fmt, self.float_io)
        return Program(
            steps=tuple(schedule([*self._steps, Step(Op.DONE)], delays)),
            constants=tuple(self._constants),
            size=self._size,
            inputs=self._inputs,
            outputs=self._outputs,
            fmt=self.fmt,
            float_io=self.float_io,
            sincos=self.sincos,
        )


def write_delay(step: Step, delays: Latencies) -> int | None:
    """Cycles from issuing `step` to the write of its word; None when it writes none."""
    if step.op == Op.MAC:
        return delays.mac if step.last else None
    if step.op == Op.LOAD:
        return delays.load
    return 0 if step.op in (Op.CONST, Op.PUT_COS, Op.PUT_SIN) else None


def schedule(steps: list[Step], delays: Latencies) -> list[Step]:
    """Steps in order, one per cycle, with no-ops so that every read follows its write.

    A word written on cycle w can be read from cycle w + 1; a step writes `write_delay` cycles
    after its issue. The memory has one write port, so no two writes share a cycle. SINCOS
    waits until no write is in flight (the engine stalls for its result, so later cycles are
    not known statically; stores run on regardless), and DONE until every write and every
    store has landed.
    """
    ready: dict[int, int] = {}
    writes: set[int] = set()
    last_write = -1
    last_store = -1
    cycle = 0
    out: list[Step] = []
    for step in steps:
        reads = {Op.MAC: (step.a, step.b), Op.SINCOS: (step.a,), Op.STORE: (step.a,)}
        start = max([cycle, *(ready.get(word, 0) for word in reads.get(step.op, ()))])
        if step.op in (Op.SINCOS, Op.DONE):
            start = max(start, last_write + 1)
        if step.op == Op.DONE:
            start = max(start, last_store)
        write = write_delay(step, delays)
        if write is not None:
            while start + write in writes:
                start += 1
            writes.add(start + write)
            ready[step.dst] = start + write + 1
            last_write = max(last_write, start + write)
        if step.op == Op.STORE:
            last_store = start + delays.store
        out += [Step(Op.NOP)] * (start - cycle)
        out.append(step)
        cycle = start + 1
    return out
