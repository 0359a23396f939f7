"""Wrappers around the open HDL tools rfc runs: MyHDL conversion, GHDL, Yosys and cocotb.

Every generated block goes through the same path — MyHDL → VHDL (and Verilog), GHDL analysis,
Yosys `synth_xilinx` on the Verilog for LUT/FF figures, cocotb on GHDL for
co-simulation — so the converters, schedulers and whole systems share these functions.

Each name is imported from its module on first use: cocotb and MyHDL take most of a second to
import, which `rfc check` and `rfc --help` need not pay.
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

#: Every name this package offers, and the module that defines it.
_MODULES = {
    "CosimError": "cocotb_sim",
    "run_cocotb": "cocotb_sim",
    "convert_myhdl": "convert",
    "elaboration": "myhdl_state",
    "start_new_design": "myhdl_state",
    "transient_signals": "myhdl_state",
    "module_instances": "modules",
    "GhdlError": "ghdl",
    "VhdlEntity": "ghdl",
    "VhdlPort": "ghdl",
    "analyze": "ghdl",
    "read_entities": "ghdl",
    "simulate": "ghdl",
    "synthesize_verilog": "ghdl",
    "synthesize_vhdl": "ghdl",
    "TimingPath": "sta",
    "ModuleEstimate": "module_estimates",
    "Resources": "yosys",
    "estimate_modules": "module_estimates",
    "estimate_resources": "yosys",
    "crossing_timing": "module_estimates",
    "estimate_timing": "yosys",
    "logic_timing": "module_estimates",
    "module_estimate": "module_estimates",
}

__all__ = sorted(_MODULES)


def __getattr__(name: str) -> Any:
    """Import the module defining `name` on first use."""
    if name in _MODULES:
        return getattr(import_module(f"rfc.toolchain.{_MODULES[name]}"), name)
    raise AttributeError(f"module 'rfc.toolchain' has no attribute '{name}'")
