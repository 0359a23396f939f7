"""The example's accelerator modules, loaded from their files, and the ports of their cores."""

from __future__ import annotations

import importlib.util
import sys
from dataclasses import dataclass
from functools import cache
from types import ModuleType
from typing import Any

from myhdl import ResetSignal, Signal, intbv

from rfc.lib.fixed import float_to_bits
from tests.conftest import ROOT

SOURCE = ROOT / "examples" / "quaternion_to_euler" / "quat_to_euler.py"
HLS = SOURCE.parent / "hls"

#: The core's ports in the order of `quat_to_euler`'s arguments.
PORT_ORDER = ("clk", "rst", "x", "y", "z", "w", "in_valid", "in_ready", "roll", "pitch", "yaw",
              "out_valid", "out_ready")  # fmt: skip


def _load(name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, SOURCE.parent / f"{name}.py")
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


@cache
def example() -> ModuleType:
    """quat_to_euler.py as a module (examples are projects, not packages; it imports its sums)."""
    _load("split_accumulator")
    return _load("quat_to_euler")


@cache
def pipelined() -> ModuleType:
    """quat_to_euler_pipelined.py as a module (it imports quat_to_euler)."""
    example()
    return _load("quat_to_euler_pipelined")


@dataclass(frozen=True)
class Core:
    """One of the two cores: its block, the precision its reference follows, its timing."""

    name: str
    block: Any
    precision: Any
    latency: int
    interval: int

    def reference(self, quaternion) -> tuple[int, int, int]:
        """The core's result bits for one (x, y, z, w) row of float64."""
        return example().reference(*(float_to_bits(float(c)) for c in quaternion), self.precision)


def cores() -> list[Core]:
    """The pipelined core (the example's default) and the iterative one."""
    fast, small = pipelined(), example()
    return [
        Core("pipelined", fast.quat_to_euler_pipelined, small.PIPELINED, fast.LATENCY, 1),
        Core("iterative", small.quat_to_euler, small.ITERATIVE, small.LATENCY,
             small.INITIATION_INTERVAL),
    ]  # fmt: skip


def core_ports() -> dict[str, Signal]:
    ports = {name: Signal(bool(0)) for name in PORT_ORDER}
    ports["rst"] = ResetSignal(0, active=1, isasync=False)
    for name in ("x", "y", "z", "w", "roll", "pitch", "yaw"):
        ports[name] = Signal(intbv(0)[64:])
    return ports


def core_arguments(ports: dict[str, Signal]) -> list[Signal]:
    return [ports[name] for name in PORT_ORDER]
