"""Field registers: each byte of a field from its lane of its chunk, with constant indices only.

The beats are those a subscriber gives: passes over the record's chunks in order, each chunk
firing once per pass, with idle cycles (any chunk number, no fire) between.
"""

from __future__ import annotations

import random
import shutil
import subprocess
import warnings
from pathlib import Path

import pytest
from myhdl import (
    ResetSignal,
    Signal,
    StopSimulation,
    ToVHDLWarning,
    always,
    block,
    delay,
    instance,
    intbv,
)

from rfc.lib.converters.fields import field_register
from rfc.lib.converters.steps import Slot, SlotRole
from rfc.lib.converters.tables import pieces
from rfc.toolchain import elaboration
from rfc.toolchain.convert import convert_myhdl

#: (bus width in bytes, slot offset in the record, slot size): one run, two runs across a
#: chunk boundary (a float64 after the CDR header on a 64-bit bus), a byte per chunk, two
#: whole chunks (a float64 after the CDR header on a 32-bit bus).
LAYOUTS = [(8, 8, 8), (8, 4, 8), (4, 2, 4), (1, 3, 4), (8, 6, 2), (1, 0, 8), (4, 4, 8)]

#: The record's first chunk number.
BASE = 2


def _runs(width: int, offset: int, size: int):
    return tuple(pieces(Slot(offset, size, SlotRole.FIELD), BASE, width))


def _passes(rng: random.Random, width: int, last: int, count: int = 4) -> list[tuple]:
    """(fire, chunk number, chunk) per cycle: `count` passes over chunks 0 to `last`."""
    beats = []
    for _ in range(count):
        for at in range(last + 1):
            while rng.random() < 0.3:
                beats.append((False, rng.randrange(last + 1), rng.randbytes(width)))
            beats.append((True, at, rng.randbytes(width)))
    return beats


def _expected(beats, offset: int, size: int, reset: int) -> list[int | None]:
    """The field after each beat, where it is settled: None while a pass is taking it in.

    A field starts at its reset value; byte b of the record is byte ``b % W`` of chunk
    ``BASE + b // W``. It is settled from the edge its last chunk passes (its bytes those of
    that pass) until its first chunk passes again.
    """
    value = bytearray(reset.to_bytes(size, "little"))
    first, last = (BASE + (offset + b) // len(beats[0][2]) for b in (0, size - 1))
    settled = True
    history: list[int | None] = []
    for fire, rc, chunk in beats:
        width = len(chunk)
        if fire:
            for b in range(size):
                position = offset + b
                if BASE + position // width == rc:
                    value[b] = chunk[position % width]
            settled = rc == last or (settled and rc != first)
        history.append(int.from_bytes(value, "little") if settled else None)
    return history


def captured(width: int, runs, target, beats) -> list[int]:
    """Simulate `field_register` into `target`: its value after the reset, then after each beat.

    The target is cleared before the reset, which must bring its own initial value back.
    """
    seen: list[int] = []

    @block
    def bench():
        clk = Signal(bool(0))
        rst = ResetSignal(0, active=1, isasync=False)
        fire = Signal(bool(0))
        rc = Signal(intbv(0, min=0, max=16))
        data = Signal(intbv(0)[8 * width :])
        dut = field_register(clk, rst, fire, rc, data, runs, target)

        @always(delay(5))
        def clock():
            clk.next = not clk

        @instance
        def drive():
            rst.next = 1
            target.next = 0
            yield clk.posedge
            rst.next = 0
            yield clk.negedge
            seen.append(int(target.val))
            for on, at, chunk in beats:
                fire.next, rc.next, data.next = on, at, int.from_bytes(chunk, "little")
                yield clk.posedge
                yield clk.negedge
                seen.append(int(target.val))
            raise StopSimulation

        return dut, clock, drive

    run = bench()
    run.run_sim(quiet=1)
    run.quit_sim()
    return seen


@pytest.mark.parametrize(("width", "offset", "size"), LAYOUTS)
def test_a_field_holds_the_bytes_of_its_chunks_from_the_edge_they_pass(width, offset, size):
    rng = random.Random(f"{width} {offset} {size}")
    reset = rng.getrandbits(8 * size)
    last = BASE + (offset + size - 1) // width + 1
    beats = _passes(rng, width, last)
    seen = captured(width, _runs(width, offset, size), Signal(intbv(reset)[8 * size :]), beats)
    expected = [reset, *_expected(beats, offset, size, reset)]
    assert [s if e is not None else None for s, e in zip(seen, expected, strict=True)] == expected


@pytest.mark.parametrize(("width", "offset", "size"), LAYOUTS)
def test_synthesis_sees_no_shifter_in_a_field_register(width, offset, size, tmp_path: Path):
    """Every slice of the bus is constant: Yosys finds no `$shiftx` cell after `proc`."""

    @block
    def capture(clk, rst, fire, rc, data, target):
        return field_register(clk, rst, fire, rc, data, _runs(width, offset, size), target)

    with elaboration(), warnings.catch_warnings():
        warnings.simplefilter("ignore", ToVHDLWarning)
        top = capture(
            Signal(bool(0)),
            ResetSignal(0, active=1, isasync=False),
            Signal(bool(0)),
            Signal(intbv(0, min=0, max=16)),
            Signal(intbv(0)[8 * width :]),
            Signal(intbv(0)[8 * size :]),
        )
        files = convert_myhdl(top, "capture", tmp_path)
    verilog = next(f for f in files if f.suffix == ".v")
    script = (
        f"read_verilog {verilog}; proc; select -assert-none t:$shiftx; select -assert-any t:$dff"
    )
    yosys = shutil.which("yosys")
    assert yosys is not None, "tools/setup.sh installs Yosys"
    run = subprocess.run([yosys, "-q", "-p", script], capture_output=True, text=True, check=False)
    assert run.returncode == 0, run.stdout + run.stderr


@pytest.mark.parametrize(("width", "offset"), [(8, 5), (4, 0), (1, 2)])
def test_a_bool_is_whether_its_byte_is_not_zero(width, offset):
    """rosbags reads any nonzero byte as true: a bool's one-bit register takes just that."""
    rng = random.Random(f"bool {width} {offset}")
    last = BASE + offset // width + 1
    beats = [
        (
            rng.random() < 0.7,
            rng.randrange(last + 1),
            bytes(rng.choice((0, 1, 2, 255)) for _ in range(width)),
        )
        for _ in range(60)
    ]
    seen = captured(width, _runs(width, offset, 1), Signal(bool(0)), beats)
    expected, value = [], False
    for on, at, chunk in beats:
        if on and at == BASE + offset // width:
            value = chunk[offset % width] != 0
        expected.append(value)
    assert seen == [False, *expected]
