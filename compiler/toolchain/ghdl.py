"""GHDL: analysis and elaboration checks, and synthesis of VHDL to netlists (VHDL, Verilog)."""

from __future__ import annotations

import functools
import os
import re
import shutil
import subprocess
import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from xml.etree import ElementTree

#: VHDL standard rfc generates and checks against.
STANDARD = "08"


class GhdlError(RuntimeError):
    """GHDL rejected generated VHDL: a bug in the generator, reported with GHDL's own words."""


def _ghdl(args: Sequence[str], workdir: Path) -> str:
    executable = _ghdl_executable()
    workdir.mkdir(parents=True, exist_ok=True)
    result = subprocess.run(
        [executable, *args], cwd=workdir, capture_output=True, text=True, check=False
    )
    if result.returncode != 0:
        raise GhdlError(f"ghdl {' '.join(args[:1])} failed:\n{result.stderr or result.stdout}")
    return result.stdout


#: GHDL's code generators, the fastest simulation first (docs/performance.md measures them):
#: llvm and gcc compile the logic to a native program once, mcode compiles it in memory at
#: every run.
BACKENDS = ("llvm", "gcc", "mcode")
#: What ``ghdl --version`` says of each.
_GENERATORS = {
    "llvm": "llvm code generator",
    "gcc": "GCC back-end",
    "mcode": "mcode code generator",
}


@dataclass(frozen=True)
class Backend:
    """One of GHDL's code generators, as installed.

    Attributes:
        name: ``llvm``, ``gcc`` or ``mcode``.
        version: The first line of ``ghdl --version`` under it.
    """

    name: str
    version: str

    @property
    def compiles(self) -> bool:
        """Whether elaboration writes a native program (llvm, gcc) that runs without GHDL."""
        return self.name != "mcode"

    def environment(self) -> dict[str, str]:
        """What selects this back-end for ``ghdl`` (Debian's ``ghdl`` reads ``GHDL_BACKEND``)."""
        return {"GHDL_BACKEND": self.name}


@functools.cache
def fastest_backend() -> Backend:
    """The fastest installed back-end, or the one ``GHDL_BACKEND`` names.

    Debian installs each back-end as ``ghdl-<name>`` beside a ``ghdl`` that runs the one
    ``GHDL_BACKEND`` names; a GHDL built from source has one back-end, which its version says.

    Raises:
        GhdlError: GHDL is not installed.
    """
    executable = _ghdl_executable()
    chosen = os.environ.get("GHDL_BACKEND", "")
    beside = [n for n in BACKENDS if os.access(Path(executable).parent / f"ghdl-{n}", os.X_OK)]
    for name in [*([chosen] if chosen in BACKENDS else beside), ""]:
        backend = _probe(executable, name)
        if backend is not None:
            return backend
    raise GhdlError(f"cannot tell the back-end of {executable}; run tools/setup.sh")


@functools.cache
def backend_named(name: str) -> Backend | None:
    """Back-end `name` (``llvm``, ``gcc``, ``mcode``) if this GHDL has it, else None.

    Whatever ``GHDL_BACKEND`` says: for a run that knows which one suits it (a long
    simulation, llvm).

    Raises:
        GhdlError: GHDL is not installed.
    """
    return _probe(_ghdl_executable(), name) if name in BACKENDS else None


def _ghdl_executable() -> str:
    executable = shutil.which("ghdl")
    if executable is None:
        raise GhdlError("ghdl is not installed; run tools/setup.sh")
    return executable


def _probe(executable: str, name: str) -> Backend | None:
    """The back-end ``ghdl`` runs under ``GHDL_BACKEND=name`` if it is that one (any, for "")."""
    result = subprocess.run(
        [executable, "--version"],
        capture_output=True,
        text=True,
        check=False,
        env={**os.environ, "GHDL_BACKEND": name},
    )
    found = next((n for n, text in _GENERATORS.items() if text in result.stdout), None)
    if found is not None and name in (found, ""):
        return Backend(found, result.stdout.splitlines()[0])
    return None


def _vhdl(files: Sequence[Path]) -> list[Path]:
    return [Path(f).resolve() for f in files if Path(f).suffix in (".vhd", ".vhdl")]


def analyze(files: Sequence[Path], workdir: Path, top: str | None = None) -> None:
    """Analyze VHDL files in order (and elaborate `top` when given).

    Raises:
        GhdlError: A file does not analyze or the design does not elaborate.
    """
    options = [f"--std={STANDARD}", "-fsynopsys", f"--workdir={workdir}"]
    _ghdl(["-a", *options, *map(str, _vhdl(files))], workdir)
    if top:
        _ghdl(["-e", *options, top], workdir)


def synthesize_verilog(files: Sequence[Path], top: str, workdir: Path) -> str:
    """Synthesize a VHDL design with `ghdl --synth` and return it as Verilog text.

    Raises:
        GhdlError: GHDL cannot synthesize the design.
    """
    return _synthesize(files, top, workdir, "verilog")


def synthesize_vhdl(files: Sequence[Path], top: str, workdir: Path) -> str:
    """Synthesize a VHDL design with `ghdl --synth` and return the netlist as VHDL text.

    The netlist keeps the entity's name and ports, so it replaces the RTL in a simulation;
    where GHDL writes a line its own analysis refuses, the line is written the way it accepts.

    Raises:
        GhdlError: GHDL cannot synthesize the design.
    """
    return _analysable(_synthesize(files, top, workdir, "vhdl"))


_BIT_SIGNAL = re.compile(r"^\s*signal (\w+)\s*:\s*std_logic;", re.M)
_BIT_TO_VECTOR = re.compile(r"std_ulogic_vector\((\w+)\)")
_CHARACTER_AS_VECTOR = re.compile(r"\b((?:un)?signed)'\('([01])'\)")


def _analysable(netlist: str) -> str:
    """Rewrite two constructs of GHDL 2.0's netlists that its own analysis refuses.

    * A ``std_logic`` signal driving a one-bit vector port, ``std_ulogic_vector(bit)`` (not
      closely related types; the 8-bit bus's ``tkeep``): written ``(0 => bit)``.
    * A one-bit vector compared with a constant, ``unsigned'('1')`` (a character literal where
      a string is needed; a one-bit counter of the DMA tap): written ``unsigned'("1")``.
    """
    bits = set(_BIT_SIGNAL.findall(netlist))
    netlist = _BIT_TO_VECTOR.sub(lambda m: f"(0 => {m[1]})" if m[1] in bits else m[0], netlist)
    return _CHARACTER_AS_VECTOR.sub(lambda m: f'{m[1]}\'("{m[2]}")', netlist)


def _synthesize(files: Sequence[Path], top: str, workdir: Path, language: str) -> str:
    options = [f"--std={STANDARD}", "-fsynopsys", f"--workdir={workdir}"]
    return _ghdl(
        ["--synth", *options, f"--out={language}", *map(str, _vhdl(files)), "-e", top], workdir
    )


@dataclass(frozen=True)
class VhdlPort:
    """A port as written in a VHDL entity.

    Attributes:
        name: Identifier, lower case (VHDL is case-insensitive).
        mode: ``in``, ``out``, ``inout`` or ``buffer``.
        bits: Width of a vector with literal bounds, 1 for a single bit, None when the bounds
            are not literals (generics).
        wire: Whether the type is ``std_logic`` (or ``std_ulogic``/``bit``).
        line: Line of the declaration.
        column: Column of the declaration.
    """

    name: str
    mode: str
    bits: int | None
    wire: bool
    line: int
    column: int


# Like the loopback's LoopbackReport in shape only: parsed VHDL.
@dataclass(frozen=True)
class VhdlEntity:
    """An entity's name, where it is declared, and its ports in order."""

    name: str
    file: Path
    line: int
    ports: tuple[VhdlPort, ...]


def read_entities(path: Path) -> list[VhdlEntity]:
    """Read the entities of a VHDL file with GHDL's own parser (``--file-to-xml``).

    Raises:
        GhdlError: The file does not parse; the message holds GHDL's diagnostics.
    """
    path = Path(path).resolve()
    with tempfile.TemporaryDirectory(prefix="rfc-ghdl-") as scratch:
        # --file-to-xml exits 0 even when the file does not parse: check the syntax first.
        _ghdl(["-s", f"--std={STANDARD}", "-fsynopsys", str(path)], Path(scratch))
        text = _ghdl(["--file-to-xml", f"--std={STANDARD}", "-fsynopsys", str(path)], Path(scratch))
    root = ElementTree.fromstring(text)
    by_id = {el.get("id"): el for el in root.iter() if el.get("id")}
    entities = []
    for unit in root.iter():
        if unit.get("kind") != "entity_declaration" or unit.get("file") not in (
            path.name,
            str(path),
        ):
            continue
        ports = []
        for port in unit.findall("port_chain/el"):
            subtype = port.find("subtype_indication")
            if subtype is not None and subtype.get("ref"):
                subtype = by_id.get(subtype.get("ref"))
            bits, wire = _port_type(subtype)
            ports.append(
                VhdlPort(
                    port.get("identifier", "").lower(),
                    port.get("mode", "in"),
                    bits,
                    wire,
                    int(port.get("line", 0)),
                    int(port.get("col", 0)),
                )
            )
        entities.append(
            VhdlEntity(
                unit.get("identifier", "").lower(), path, int(unit.get("line", 0)), tuple(ports)
            )
        )
    return entities


_WIRE_TYPES = {"std_logic", "std_ulogic", "bit"}


def _port_type(subtype: ElementTree.Element | None) -> tuple[int | None, bool]:
    if subtype is None:
        return None, False
    if subtype.get("kind") == "simple_name":
        return (1, True) if subtype.get("identifier", "").lower() in _WIRE_TYPES else (None, False)
    for node in subtype.iter():
        if node.get("kind") == "range_expression":
            limits = [node.find(f"{side}_limit_expr") for side in ("left", "right")]
            if all(
                limit is not None and limit.get("kind") == "integer_literal" for limit in limits
            ):
                left, right = (int(limit.get("value", "0")) for limit in limits)  # type: ignore[union-attr]
                return abs(left - right) + 1, False
            return None, False
    return None, False


def simulate(
    files: Sequence[Path], top: str, workdir: Path, generics: Mapping[str, object] | None = None
) -> str:
    """Analyze and elaborate VHDL files, run the testbench `top` to its end, return its output.

    Args:
        files: VHDL files in compile order, the testbench among them.
        top: The testbench entity; it must stop by itself.
        workdir: GHDL's work folder.
        generics: Values for the testbench's generics.

    Raises:
        GhdlError: The design does not analyze or elaborate, or the run fails.
    """
    analyze(files, workdir, top)
    options = [f"--std={STANDARD}", "-fsynopsys", f"--workdir={workdir}"]
    assignments = [f"-g{name}={value}" for name, value in (generics or {}).items()]
    # numeric_std's warnings (metavalues before reset, truncations MyHDL's conversion relies on)
    # would fill the captured output with millions of lines over a long run.
    return _ghdl(["-r", *options, top, *assignments, "--ieee-asserts=disable"], workdir)
