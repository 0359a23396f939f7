"""The 4x4 homogeneous-transform product on the shared engine: program and MyHDL block.

Transforms travel as their top three rows, row-major (12 raw words of one `FixedFormat`); the
bottom row is (0, 0, 0, 1). Entry (r, j) of ``A·B`` is ``Σ_k A[r][k]·B[k][j]`` over k < 3, plus
``A[r][3]`` when j = 3, rounded half up once (`rfc.lib.arith.mac`): 39 products through one
multiply-accumulate unit.
"""

from __future__ import annotations

from myhdl import block

from rfc.lib.arith.engine import Program, ProgramBuilder
from rfc.lib.arith.engine_hdl import engine
from rfc.lib.fixed import FixedFormat
from rfc.lib.types import Instances, SignalLike

#: Entries of a transform as it travels: the top three rows.
ENTRIES = 12


def transform_product(builder: ProgramBuilder, a: list[int], b: list[int], one: int) -> list[int]:
    """Words of ``A·B`` (row-major top rows) from words of A and B; `one` holds 1.0."""
    out = []
    for r in range(3):
        for j in range(4):
            terms = [(a[4 * r + k], b[4 * k + j]) for k in range(3)]
            if j == 3:
                terms.append((a[4 * r + 3], one))
            out.append(builder.dot(terms))
    return out


def transform_program(fmt: FixedFormat) -> Program:
    """Load A then B (12 words each), store ``A·B`` (12 words)."""
    builder = ProgramBuilder(fmt)
    a = [builder.load() for _ in range(ENTRIES)]
    b = [builder.load() for _ in range(ENTRIES)]
    one = builder.constant(1 << fmt.frac_bits)
    for word in transform_product(builder, a, b, one):
        builder.store(word)
    return builder.build()


# Signatures alike across rfc.lib blocks are its handshake convention, not a repeated idea.
@block
def transform_multiply(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    a: SignalLike,
    b: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    c: SignalLike,
    fmt: FixedFormat,
) -> Instances:
    """``C = A·B`` of homogeneous transforms in `fmt`, sequential on one multiply-accumulate.

    Ports: clock and handshakes named as in `rfc.lib.arith.pipeline`.

    Args:
        a: 12 input signals of `fmt`: A's top three rows, row-major.
        b: 12 input signals of `fmt`: B's top three rows, row-major.
        c: 12 output signals of `fmt`: C's top three rows, row-major.
        fmt: The entries' fixed-point format (1.0 must be representable).
    """
    program = transform_program(fmt)
    return engine(clk, rst, in_valid, in_ready, [*a, *b], out_valid, out_ready, c, program)
