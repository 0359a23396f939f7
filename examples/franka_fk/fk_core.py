"""The Panda's forward kinematics in hardware: a program for rfc.lib.arith's shared engine.

For a robot state (7 joint positions, F_T_EE and O_T_EE as float64 bit patterns) the core
gives T1…T7 (base to joint i, column-major) and the mean squared difference between
T7 · T_flange · F_T_EE and O_T_EE. Inside, every value is fixed point `WORD` (Q6.44): joint
sines and cosines from the CORDIC unit, link transforms built from them and Franka's
modified-DH constants (the twists are multiples of π/2, so their sines and cosines are exact
0 and ±1 and most products vanish), chained through one multiply-accumulate unit. Inputs and
results must stay within ±32 (the arm's reach is 1.2 m), joint positions within ±8 rad.
"""

from __future__ import annotations

from functools import cache

from myhdl import block

from rfc.lib.arith import SinCosConfig
from rfc.lib.arith.engine import Program, ProgramBuilder, run
from rfc.lib.arith.engine_hdl import engine
from rfc.lib.fixed import FixedFormat, float_to_bits, float_to_fixed

WORD = FixedFormat(50, 44)
SINCOS = SinCosConfig(WORD.frac_bits)
A = (0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088)
D = (0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0)
#: Twists as multiples of π/2 (0, -π/2, π/2, ...).
TWIST_QUARTERS = (0, -1, 1, 1, -1, 1, 1)
FLANGE = 0.107
JOINTS = 7


class _Writer:
    """Builds the program: words for constants, signed sines and cosines, transform products."""

    def __init__(self) -> None:
        self.b = ProgramBuilder(WORD, float_io=True, sincos=SINCOS)

    def const(self, value: float) -> int | None:
        """A word holding `value` (as the input converter would round it); None for 0."""
        if value == 0:
            return None
        return self.b.constant(float_to_fixed(float_to_bits(value), WORD).raw)

    def zero(self) -> int:
        return self.b.constant(0)

    def link(self, cos: int, sin: int, index: int) -> list[int | None]:
        """The link transform's top rows (row-major) as words; None where the entry is 0."""
        minus_one = self.const(-1.0)
        neg_cos, neg_sin = self.b.dot([(cos, minus_one)]), self.b.dot([(sin, minus_one)])
        quarters = TWIST_QUARTERS[index] % 4
        ca, sa = (1, 0, -1, 0)[quarters], (0, 1, 0, -1)[quarters]

        def times(word: int, negated: int, sign: int) -> int | None:
            return {1: word, -1: negated, 0: None}[sign]

        d = D[index]
        return [
            cos, neg_sin, None, self.const(A[index]),
            times(sin, neg_sin, ca), times(cos, neg_cos, ca), self.const(-sa), self.const(-sa * d),
            times(sin, neg_sin, sa), times(cos, neg_cos, sa), self.const(ca), self.const(ca * d),
        ]  # fmt: skip

    def chain(self, left: list[int], right: list[int | None]) -> list[int]:
        """Top rows of ``left · right`` (homogeneous), skipping the products with zeros."""
        one = self.const(1.0)
        out = []
        for r in range(3):
            for j in range(4):
                terms = [(left[4 * r + k], right[4 * k + j]) for k in range(3)]
                if j == 3:
                    terms.append((left[4 * r + 3], one))
                out.append(self.b.dot([(x, y) for x, y in terms if y is not None]))
        return out


@cache
def fk_program() -> Program:
    """The core's program: 39 inputs (q, F_T_EE, O_T_EE), 113 outputs (T1…T7, mse)."""
    w = _Writer()
    b = w.b
    q = [b.load() for _ in range(JOINTS)]
    f_t_ee = [b.load() for _ in range(16)]
    o_t_ee = [b.load() for _ in range(16)]
    angles = [b.cos_sin(joint) for joint in q]
    frames: list[list[int]] = []
    for i, (cos, sin) in enumerate(angles):
        link = w.link(cos, sin, i)
        if frames:
            frames.append(w.chain(frames[-1], link))
        else:
            frames.append([w.zero() if word is None else word for word in link])
    last, one = frames[-1], w.const(1.0)
    flange = list(last)
    for r in range(3):
        flange[4 * r + 3] = b.dot([(last[4 * r + 3], one), (last[4 * r + 2], w.const(FLANGE))])
    # T7 · T_flange · F_T_EE as a full 4x4 product (F_T_EE's bottom row taken as sent).
    end = [
        b.dot([(flange[4 * r + k], f_t_ee[4 * j + k]) for k in range(4)])
        if r < 3
        else f_t_ee[4 * j + 3]
        for r in range(4)
        for j in range(4)
    ]
    quarter, minus_quarter = w.const(0.25), w.const(-0.25)
    halves = [
        b.dot([(end[4 * r + j], quarter), (o_t_ee[4 * j + r], minus_quarter)])
        for r in range(4)
        for j in range(4)
    ]
    mse = b.dot([(h, h) for h in halves])
    bottom = (w.zero(), w.zero(), w.zero(), w.const(1.0))
    for frame in frames:
        for j in range(4):
            for r in range(4):
                b.store(frame[4 * r + j] if r < 3 else bottom[j])
    b.store(mse)
    return b.build()


def fk_model(q: list, f_t_ee: list, o_t_ee: list) -> tuple[list, object]:
    """The core's outputs, bit for bit: 112 transform entries and the mse (float64 patterns).

    Takes ints, or NumPy arrays of them to compute a batch (outputs are arrays then).
    """
    out = run(fk_program(), [*q, *f_t_ee, *o_t_ee])
    return out[:-1], out[-1]


@block
def fk_core(clk, rst, q, f_t_ee, o_t_ee, in_valid, in_ready, transforms, mse, out_valid, out_ready):
    """Forward kinematics of one robot state per message (bits of `fk_model`).

    Args:
        clk: Clock.
        rst: Synchronous reset (a MyHDL ``ResetSignal``).
        q: 7 input signals, the joint positions (rad).
        f_t_ee: 16 input signals, the flange-to-end-effector transform, column-major.
        o_t_ee: 16 input signals, the measured base-to-end-effector transform, column-major.
        in_valid: Input, the inputs hold a state to take.
        in_ready: Output, the core takes the state on this cycle when `in_valid` is high.
        transforms: 112 output signals: T1…T7, each column-major.
        mse: Output, mean over the 16 entries of (T7 · T_flange · F_T_EE - O_T_EE)².
        out_valid: Output, the outputs hold a result.
        out_ready: Input, the consumer takes the result on this cycle.

    Every value is a float64 bit pattern (``Signal(intbv(0)[64:])``).
    """
    inputs = [*q, *f_t_ee, *o_t_ee]
    outputs = [*transforms, mse]
    return engine(clk, rst, in_valid, in_ready, inputs, out_valid, out_ready, outputs, fk_program())
