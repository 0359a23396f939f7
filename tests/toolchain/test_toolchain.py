"""The HDL toolchain wrappers on a small design: conversion, GHDL, Yosys, cocotb."""

from __future__ import annotations

import pytest

from rfc.toolchain import (
    CosimError,
    GhdlError,
    analyze,
    convert_myhdl,
    estimate_resources,
    run_cocotb,
)
from tests.toolchain.counter import counter_instance


@pytest.fixture
def counter_files(tmp_path):
    return convert_myhdl(counter_instance(), "counter8", tmp_path / "hdl", header="rfc test")


def test_conversion_is_reproducible(tmp_path, counter_files):
    again = convert_myhdl(counter_instance(), "counter8", tmp_path / "again", header="rfc test")
    assert [f.name for f in counter_files] == ["pck_myhdl_011.vhd", "counter8.vhd", "counter8.v"]
    for first, second in zip(counter_files, again, strict=True):
        assert first.read_text() == second.read_text()
    assert counter_files[1].read_text().startswith("-- rfc test\n")
    assert "Date" not in counter_files[1].read_text()


def test_ghdl_analyzes_and_elaborates(tmp_path, counter_files):
    analyze(counter_files, tmp_path / "work", top="counter8")


def test_ghdl_reports_bad_vhdl(tmp_path):
    bad = tmp_path / "bad.vhd"
    bad.write_text("entity bad is port (a : in bit) end;\n")
    with pytest.raises(GhdlError, match="failed"):
        analyze([bad], tmp_path / "work")


def test_yosys_counts_an_eight_bit_counter(counter_files):
    resources = estimate_resources(counter_files, "counter8")
    assert resources.ff == 8
    assert 0 < resources.lut + resources.carry <= 16


def test_cocotb_passes_and_fails(tmp_path, counter_files):
    ran = run_cocotb(counter_files, "counter8", "tests.toolchain.counter", tmp_path / "ok")
    assert ran == 1
    with pytest.raises(CosimError, match="count 7 != 8"):
        run_cocotb(
            counter_files,
            "counter8",
            "tests.toolchain.counter",
            tmp_path / "fail",
            env={"COUNTER_CYCLES": "7", "COUNTER_EXPECT": "8"},
        )
