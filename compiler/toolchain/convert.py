"""MyHDL → VHDL and Verilog, reproducibly (no dates in headers) and into a chosen folder."""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

from myhdl import _block as myhdl_block

#: MyHDL's converters are module-level singletons configured by attributes: one at a time.
_CONVERTER_LOCK = threading.Lock()


def start_new_design() -> None:
    """Start MyHDL's instance naming afresh before elaborating a new design.

    MyHDL keeps every instance name it ever gave in module-level sets and makes a repeated name
    unique by appending a suffix per repetition, so a process elaborating many designs (a sweep,
    a test worker) gets names that grow without bound until GHDL rejects them, and that differ
    from run to run. Names need only be unique within one design. Call this before calling the
    top-level block function.
    """
    myhdl_block._name_set.clear()
    myhdl_block._inst_name_set.clear()


#: The support package every MyHDL-generated VHDL file uses.
MYHDL_PACKAGE = "pck_myhdl_011.vhd"


def convert_myhdl(
    instance: Any,
    name: str,
    directory: Path,
    *,
    verilog: bool = True,
    header: str = "",
) -> list[Path]:
    """Convert an elaborated MyHDL block instance to VHDL (and Verilog).

    Ports become `std_logic`/`std_logic_vector`, the way other VHDL instantiates them.

    Args:
        instance: The result of calling a ``@block`` function with its signals.
        name: Entity/module name and file stem.
        directory: Output folder, created when missing.
        verilog: Also write ``name.v`` (without MyHDL's test bench).
        header: Comment text put at the top of each file instead of MyHDL's dated banner.

    Returns:
        The VHDL files in compile order (MyHDL's package first), then the Verilog file.
    """
    directory.mkdir(parents=True, exist_ok=True)
    banner = "".join(f"-- {line}\n" for line in header.splitlines())
    with _CONVERTER_LOCK:
        instance.convert(
            hdl="VHDL",
            path=str(directory),
            name=name,
            std_logic_ports=True,
            no_myhdl_header=True,
            header=banner,
        )
        files = [directory / MYHDL_PACKAGE, directory / f"{name}.vhd"]
        if verilog:
            instance.convert(
                hdl="Verilog",
                path=str(directory),
                name=name,
                testbench=False,
                no_myhdl_header=True,
                header=banner.replace("--", "//"),
            )
            files.append(directory / f"{name}.v")
    return files
