"""Wrappers around the open HDL tools rfc runs: MyHDL conversion, GHDL, Yosys and cocotb.

Every generated block goes through the same path — MyHDL → VHDL (and Verilog), GHDL analysis,
Yosys `synth_xilinx` on the Verilog for LUT/FF figures, cocotb on GHDL for
co-simulation — so the converters, schedulers and whole systems share these functions.
"""

from rfc.toolchain.cocotb_sim import CosimError, run_cocotb
from rfc.toolchain.convert import convert_myhdl, start_new_design
from rfc.toolchain.ghdl import (
    GhdlError,
    VhdlEntity,
    VhdlPort,
    analyze,
    read_entities,
    simulate,
    synthesize_verilog,
    synthesize_vhdl,
)
from rfc.toolchain.sta import TimingPath
from rfc.toolchain.yosys import (
    ModuleEstimate,
    Resources,
    estimate_modules,
    estimate_resources,
    estimate_timing,
    module_estimate,
    system_timing,
)

__all__ = [
    "CosimError",
    "GhdlError",
    "ModuleEstimate",
    "Resources",
    "TimingPath",
    "VhdlEntity",
    "VhdlPort",
    "analyze",
    "convert_myhdl",
    "estimate_modules",
    "estimate_resources",
    "estimate_timing",
    "module_estimate",
    "read_entities",
    "run_cocotb",
    "simulate",
    "start_new_design",
    "synthesize_verilog",
    "synthesize_vhdl",
    "system_timing",
]
