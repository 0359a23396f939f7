"""MyHDL → VHDL and Verilog, reproducibly (no dates in headers) and into a chosen folder."""

from __future__ import annotations

import re
import tempfile
import threading
from collections.abc import Callable
from pathlib import Path
from typing import Any

from rfc.toolchain.modules import separate_modules
from rfc.toolchain.myhdl_state import start_new_design

#: MyHDL's converters are module-level singletons configured by attributes: one at a time.
_CONVERTER_LOCK = threading.Lock()


#: The support package every MyHDL-generated VHDL file uses.
MYHDL_PACKAGE = "pck_myhdl_011.vhd"


def convert_myhdl(
    instance: Any,
    name: str,
    directory: Path,
    *,
    verilog: bool = True,
    header: str = "",
    separate: Callable[[Any], bool] | None = None,
) -> list[Path]:
    """Convert an elaborated MyHDL block instance to VHDL (and Verilog).

    Ports become `std_logic`/`std_logic_vector`, the way other VHDL instantiates them. Every
    signal gets its MyHDL initial value (FPGA registers power up with it), so no output is
    undefined before the first reset edge.

    Args:
        instance: The result of calling a ``@block`` function with its signals.
        name: Entity/module name and file stem.
        directory: Output folder, created when missing.
        verilog: Also write ``name.v`` (without MyHDL's test bench).
        header: Comment text put at the top of each file instead of MyHDL's dated banner.
        separate: Which sub-blocks the Verilog holds as modules of their own
            (`rfc.toolchain.modules`), each in a file beside ``name.v``; none when None.

    Returns:
        The VHDL files in compile order (MyHDL's package first), then the Verilog files (the
        separate modules first, ``name.v`` last).
    """
    directory.mkdir(parents=True, exist_ok=True)
    banner = "".join(f"-- {line}\n" for line in header.splitlines())
    marks = _user_marks(instance)
    with _CONVERTER_LOCK:
        _convert(instance, "VHDL", directory / name, banner, std_logic_ports=True)
        files = [directory / MYHDL_PACKAGE, directory / f"{name}.vhd"]
        _drop_undeclared_port_copies(files[1])
        if verilog:
            for signal, driven, read in marks:  # the VHDL conversion cleared them
                signal._driven, signal._read = driven, read
            chosen = separate or (lambda _: False)
            with separate_modules(instance, chosen, _module_text) as modules:
                for module in modules:
                    files.append(directory / f"{module.name}.v")
                    files[-1].write_text(module.text)
                _verilog(instance, directory / name, files[1], banner.replace("--", "//"))
            files.append(directory / f"{name}.v")
    return files


def _verilog(instance: Any, stem: Path, vhdl: Path, header: str) -> None:
    """Convert to ``stem.v``, mended where MyHDL's Verilog differs from its VHDL (`vhdl`)."""
    _convert(instance, "Verilog", stem, header, testbench=False)
    verilog = stem.with_suffix(".v")
    _indexed_part_selects(verilog)
    _negative_literals(verilog)
    _signed_constants(verilog, vhdl)


def _module_text(elaborate: Callable[[], Any], name: str) -> str:
    """The Verilog of a separate module (`rfc.toolchain.modules`), converted in a scratch folder.

    Its instance names start afresh, so that they do not depend on what came before it.
    """
    start_new_design()
    instance = elaborate()
    with tempfile.TemporaryDirectory(prefix="rfc-module-") as scratch:
        stem = Path(scratch) / name
        _convert(instance, "VHDL", stem, "", std_logic_ports=True)
        _verilog(instance, stem, stem.with_suffix(".vhd"), "")
        return stem.with_suffix(".v").read_text()


def _convert(instance: Any, hdl: str, stem: Path, header: str, **options: bool) -> None:
    """One MyHDL conversion to `stem` (folder and name), with rfc's options for every HDL."""
    instance.convert(
        hdl=hdl,
        path=str(stem.parent),
        name=stem.name,
        initial_values=True,
        no_myhdl_header=True,
        header=header,
        **options,
    )


_LOOP_SLICE = re.compile(r"\[\(\((\w+) \+ 1\) \* (\d+)\)-1:\(\1 \* \2\)\]")


def _indexed_part_selects(path: Path) -> None:
    """Write MyHDL's slices at a loop index, ``x[((i + 1) * 8)-1:(i * 8)]``, as ``x[(i * 8) +: 8]``.

    Verilog-2001 wants constant bounds in a part select; Yosys reads MyHDL's form anyway, but
    Verilator refuses it. The indexed part select means the same bits.
    """
    text = path.read_text()
    fixed = _LOOP_SLICE.sub(lambda m: f"[({m.group(1)} * {m.group(2)}) +: {m.group(2)}]", text)
    if fixed != text:
        path.write_text(fixed)


_NEGATIVE_LITERAL = re.compile(r"\b(\d+)'d-(\d+)\b")


def _negative_literals(path: Path) -> None:
    """Write MyHDL's negative sized constants, ``50'd-5``, as Verilog does: ``-50'sd5``.

    MyHDL (0.11.52) prints the sign after the base, which Verilator refuses ("Number is missing
    value digits"); the negated signed literal gives the same two's-complement bits and stays
    signed in comparisons.
    """
    text = path.read_text()
    fixed = _NEGATIVE_LITERAL.sub(lambda m: f"-{m.group(1)}'sd{m.group(2)}", text)
    if fixed != text:
        path.write_text(fixed)


_SIGNED_VHDL = re.compile(r"^\s*(?:signal|constant) (\w+)\s*:\s*signed\b", re.M)
_UNSIGNED_CONSTANT = re.compile(r"^(\s*(?:wire|localparam) )(\[\d+:0\] \w+)\b", re.M)


def _signed_constants(verilog: Path, vhdl: Path) -> None:
    """Declare MyHDL's signed constants signed in the Verilog, as its VHDL of the design does.

    MyHDL (0.11.52) writes a signal that nothing drives as a wire tied to its initial value,
    and a ``Constant`` as a localparam, but leaves ``signed`` out of both declarations (it
    writes it for every other signal). Verilog then compares a signed operand with such a
    constant as unsigned, so a negative bound reads as a large positive one. Both conversions
    name the design's signals alike, and the VHDL declares the constant ``signed``.
    """
    signed = set(_SIGNED_VHDL.findall(vhdl.read_text()))
    text = verilog.read_text()
    fixed = _UNSIGNED_CONSTANT.sub(
        lambda m: f"{m.group(1)}signed {m.group(2)}" if m.group(2).split()[1] in signed else m[0],
        text,
    )
    if fixed != text:
        verilog.write_text(fixed)


def _user_marks(instance: Any) -> list[tuple[Any, Any, bool]]:
    """Every signal of the design with the `driven`/`read` marks set when it was elaborated.

    A block given as user-defined HDL (a memory template) marks the signals its template
    drives and reads. MyHDL clears those marks at the end of each conversion, so a second
    conversion of the same instance would take a driven output for an undriven wire (and tie
    it to 0): they are put back before it.
    """
    marks = []
    blocks = [instance]
    while blocks:
        block = blocks.pop()
        signals = list(getattr(block, "sigdict", {}).values())
        for memory in getattr(block, "memdict", {}).values():
            signals += list(getattr(memory, "mem", memory))
        marks += [(s, s._driven, s._read) for s in signals if hasattr(s, "_driven")]
        blocks += [sub for sub in getattr(block, "subs", ()) if hasattr(sub, "subs")]
    return marks


_PORT_COPY = re.compile(r"^(\w+)_num <= (?:unsigned|signed)\(\1\);\n", re.M)


def _drop_undeclared_port_copies(path: Path) -> None:
    """Remove MyHDL's copies of unread vector inputs into signals it never declares.

    With ``std_logic_ports`` myhdl 0.11.52 converts each vector input ``p`` to ``p_num`` inside
    the architecture, but declares ``p_num`` only when something reads it: an input the design
    ignores (a field an accelerator does not use) leaves an assignment GHDL rejects.
    """
    text = path.read_text()
    declared = set(re.findall(r"^\s*signal (\w+)\s*:", text, re.M))
    kept = _PORT_COPY.sub(lambda m: m.group(0) if f"{m.group(1)}_num" in declared else "", text)
    if kept != text:
        path.write_text(kept)


_SENSITIVITY = re.compile(r"@\(([^)]*)\)")


def canonical_lines(text: str) -> list[str]:
    """The lines of MyHDL's Verilog in an order that does not depend on the process: a key.

    MyHDL orders sensitivity lists and reset branches by Python's string hashing, which
    changes from process to process, so the same design comes in different orders: sorting
    the names of each sensitivity list and then the lines gives one text per design.
    """

    def ordered(match: re.Match[str]) -> str:
        return "@(" + ", ".join(sorted(n.strip() for n in match.group(1).split(","))) + ")"

    return sorted(_SENSITIVITY.sub(ordered, line) for line in text.splitlines())
