"""Field registers: each byte of a field from its lane of its chunk, with constant indices only."""

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
from rfc.lib.converters.toplevel import elaboration
from rfc.toolchain.convert import convert_myhdl

#: (bus width in bytes, slot offset in the record, slot size): one run, two runs across a
#: chunk boundary (a float64 after the CDR header on a 64-bit bus), a byte per chunk.
LAYOUTS = [(8, 8, 8), (8, 4, 8), (4, 2, 4), (1, 3, 4), (8, 6, 2)]

#: The record's first chunk number.
BASE = 2


def _runs(width: int, offset: int, size: int):
    return tuple(pieces(Slot(offset, size, SlotRole.FIELD), BASE, width))


def _expected(beats, offset: int, size: int, reset: int) -> list[int]:
    """The field after each beat: its bytes once the record's chunks holding them have passed.

    A field starts at its reset value; byte b of the record is byte ``b % W`` of chunk
    ``BASE + b // W``, and a byte is taken whenever that chunk fires.
    """
    value = bytearray(reset.to_bytes(size, "little"))
    history = []
    for fire, rc, chunk in beats:
        width = len(chunk)
        if fire:
            for b in range(size):
                position = offset + b
                if BASE + position // width == rc:
                    value[b] = chunk[position % width]
        history.append(int.from_bytes(value, "little"))
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
    beats = [(rng.random() < 0.7, rng.randrange(last + 1), rng.randbytes(width)) for _ in range(60)]
    seen = captured(width, _runs(width, offset, size), Signal(intbv(reset)[8 * size :]), beats)
    assert seen == [reset, *_expected(beats, offset, size, reset)]


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
