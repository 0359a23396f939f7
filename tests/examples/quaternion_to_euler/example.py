"""The example accelerator module, loaded from its file, and the ports of its core."""

from __future__ import annotations

import importlib.util
import sys
from functools import cache
from types import ModuleType

from myhdl import ResetSignal, Signal, intbv

from tests.conftest import ROOT

SOURCE = ROOT / "examples" / "quaternion_to_euler" / "quat_to_euler.py"
HLS = SOURCE.parent / "hls"

#: The core's ports in the order of `quat_to_euler`'s arguments.
PORT_ORDER = ("clk", "rst", "x", "y", "z", "w", "in_valid", "in_ready", "roll", "pitch", "yaw",
              "out_valid", "out_ready")  # fmt: skip


@cache
def example() -> ModuleType:
    """quat_to_euler.py as a module (examples are projects, not packages)."""
    spec = importlib.util.spec_from_file_location("quat_to_euler", SOURCE)
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def core_ports() -> dict[str, Signal]:
    ports = {name: Signal(bool(0)) for name in PORT_ORDER}
    ports["rst"] = ResetSignal(0, active=1, isasync=False)
    for name in ("x", "y", "z", "w", "roll", "pitch", "yaw"):
        ports[name] = Signal(intbv(0)[64:])
    return ports


def core_arguments(ports: dict[str, Signal]) -> list[Signal]:
    return [ports[name] for name in PORT_ORDER]
