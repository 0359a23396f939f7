"""What both front-ends share: defaults, and the conversion of spec values into IR values.

The YAML and the Python form of one system must lower to the same IR, so every default and
every conversion (middleware spellings, durations, source paths, FPGA family) lives here once.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path

from rfc.errors import RfcError, SourceLocation, did_you_mean
from rfc.ir.model import SCHEDULER_ALGORITHMS, AcceleratorKind, FunctionRef
from rfc.messages.limits import MAX_LENGTH, Limits
from rfc.messages.rosbags_adapter import DEFAULT_DISTRO, DISTROS, Middleware
from rfc.spec import parts
from rfc.spec.python_names import check_defines
from rfc.spec.text_files import binary_reason

DEFAULT_FPGA_PART = "xc7z020clg400-1"
DEFAULT_MIDDLEWARE = Middleware.ROS2
DEFAULT_BUS_WIDTH = 64
DEFAULT_CLOCK_MHZ = 100.0
DEFAULT_SCHEDULER = "auto"

_MIDDLEWARES = {
    "ros": Middleware.ROS1,
    "ros1": Middleware.ROS1,
    "ros 1": Middleware.ROS1,
    "ros2": Middleware.ROS2,
    "ros 2": Middleware.ROS2,
}
#: Source file suffixes each accelerator kind is written in.
SOURCE_SUFFIXES = {
    AcceleratorKind.HLS: (".cpp", ".cc", ".cxx", ".c", ".h", ".hpp"),
    AcceleratorKind.VHDL: (".vhd", ".vhdl"),
    AcceleratorKind.MYHDL: (".py",),
    AcceleratorKind.ROS_SW: (".py", ".cpp", ".cc", ".cxx", ".c", ".h", ".hpp"),
}
_DURATION = re.compile(r"^\s*([0-9]+(?:\.[0-9]*)?|\.[0-9]+)\s*(ns|us|µs|ms|s)\s*$")
_SECONDS = {"ns": 1e-9, "us": 1e-6, "µs": 1e-6, "ms": 1e-3, "s": 1.0}


def middleware(text: str, location: SourceLocation) -> Middleware:
    """Read a middleware as the paper and the spec spell it (``ROS`` is ROS 1)."""
    found = _MIDDLEWARES.get(str(text).strip().lower())
    if found is None:
        raise RfcError(
            f"unknown middleware '{text}'; expected ROS (ROS 1) or ROS2",
            location=location,
            hint=did_you_mean(str(text), ["ROS", "ROS1", "ROS2"]),
        )
    return found


def distro(name: str | None, chosen: Middleware, location: SourceLocation) -> str:
    """The type store to use: the one named (checked), or the middleware's default."""
    if name is None:
        return DEFAULT_DISTRO[chosen]
    if name not in DISTROS[chosen]:
        raise RfcError(
            f"unknown {chosen.label} distro '{name}'; expected one of {', '.join(DISTROS[chosen])}",
            location=location,
            hint=did_you_mean(name, DISTROS[chosen]),
        )
    return name


def fpga_family(part: str, location: SourceLocation) -> str:
    """Derive the device family from a part number, as the paper's tool does."""
    return parts.fpga_family(part, location)


def bus_width(width: int, location: SourceLocation) -> int:
    """Check a DMA bus width."""
    if width not in (8, 32, 64):
        raise RfcError(
            f"bus width must be 8, 32 or 64 bits, not {width}",
            location=location,
        )
    return width


#: The clocks a Zynq's programmable logic can run at, in MHz (its fabric tops out below 1 GHz).
CLOCK_RANGE_MHZ = (1.0, 1000.0)


def clock_mhz(value: float, location: SourceLocation) -> float:
    """Check a clock frequency: a real one, within `CLOCK_RANGE_MHZ`."""
    low, high = CLOCK_RANGE_MHZ
    if not low <= value <= high:  # also refuses NaN
        raise RfcError(
            f"clock must be from {low:g} to {high:g} MHz, not {value}",
            location=location,
            hint="Zynq logic typically runs at 50 to 250 MHz; the default is "
            f"{DEFAULT_CLOCK_MHZ:g}",
        )
    return float(value)


def scheduler(name: str, location: SourceLocation) -> str:
    """Return the canonical spelling of a scheduling algorithm."""
    for algorithm in SCHEDULER_ALGORITHMS:
        if algorithm.lower() == str(name).strip().lower():
            return algorithm
    raise RfcError(
        f"unknown scheduler '{name}'; expected one of {', '.join(SCHEDULER_ALGORITHMS)}",
        location=location,
        hint=did_you_mean(str(name), SCHEDULER_ALGORITHMS),
    )


def accelerator_kind(name: str, location: SourceLocation) -> AcceleratorKind:
    """Return the accelerator kind written as ``HLS``, ``VHDL``, ``MyHDL`` or ``ROS-SW``."""
    for kind in AcceleratorKind:
        if kind.value.lower() == str(name).strip().lower():
            return kind
    options = [k.value for k in AcceleratorKind]
    raise RfcError(
        f"unknown accelerator type '{name}'; expected one of {', '.join(options)}",
        location=location,
        hint=did_you_mean(str(name), options),
    )


def cycles(value: int | float | str, clock: float, what: str, location: SourceLocation) -> int:
    """Convert a period or deadline to clock cycles (rounded up).

    An integer is already in cycles; a string carries a unit (``10 us``, ``1.5ms``).
    """
    if isinstance(value, bool) or not isinstance(value, int | str):
        raise RfcError(
            f"{what} must be clock cycles (an integer) or a duration such as '10 us', "
            f"not {value!r}",
            location=location,
        )
    if isinstance(value, str):
        match = _DURATION.match(value)
        if match is None:
            raise RfcError(
                f"{what} must be clock cycles (an integer) or a duration such as '10 us', "
                f"not '{value}'",
                location=location,
                hint="units: ns, us, ms, s",
            )
        seconds = float(match[1]) * _SECONDS[match[2]]
        value = math.ceil(round(seconds * clock * 1e6, 6))
    if value < 1:
        raise RfcError(f"{what} must be at least one clock cycle, not {value}", location=location)
    return value


def positive(value: int, what: str, location: SourceLocation) -> int:
    """Check a positive integer such as ``maxBytes``."""
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise RfcError(f"{what} must be a positive integer, not {value!r}", location=location)
    return value


#: Set while `rfc stub` reads a spec whose accelerator sources are not written yet.
_SOURCES_MAY_BE_MISSING: ContextVar[bool] = ContextVar("sources_may_be_missing", default=False)


@contextmanager
def sources_may_be_missing() -> Iterator[None]:
    """Accept source files that do not exist yet (to print their skeletons), in this context."""
    token = _SOURCES_MAY_BE_MISSING.set(True)
    try:
        yield
    finally:
        _SOURCES_MAY_BE_MISSING.reset(token)


def source_file(text: str, base: Path, what: str, location: SourceLocation) -> Path:
    """Resolve a path written in the spec against the spec's directory; it must exist."""
    path = (base / str(text)).resolve()
    missing_allowed = what in ("source file", "reference file") and _SOURCES_MAY_BE_MISSING.get()
    if not path.exists() and not missing_allowed:
        raise RfcError(
            f"{what} '{text}' does not exist",
            location=location,
            hint="paths are relative to the folder of the spec",
        )
    return path


def message_directory(text: str, base: Path, location: SourceLocation) -> Path:
    """Resolve a ``msg_paths`` entry against the spec's directory; it must be a directory."""
    path = source_file(text, base, "message directory", location)
    if not path.is_dir():
        raise RfcError(f"message directory '{text}' is not a directory", location=location)
    return path


def check_source_suffixes(
    kind: AcceleratorKind, sources: list[tuple[Path, SourceLocation]], owner: str
) -> None:
    """Check that each source file is text in a language the accelerator kind uses."""
    allowed = SOURCE_SUFFIXES[kind]
    for path, location in sources:
        if path.suffix.lower() not in allowed:
            raise RfcError(
                f"{owner} is {kind.value}, whose sources end in {', '.join(allowed)}; "
                f"'{path.name}' does not",
                location=location,
            )
        reason = binary_reason(path) if path.is_file() else None
        if reason is not None:
            raise RfcError(
                f"'{path.name}' is not a source: it is binary, not {kind.value} text ({reason})",
                location=location,
                hint=f"name the {kind.value} source files of {owner}",
            )


def default_topic(block_name: str) -> str:
    """The topic of a converter whose spec names none: ``/<block name>``."""
    return f"/{block_name}"


def default_port_name(direction: str, index: int) -> str:
    """Name of an unnamed port: ``in0``, ``in1``, ... or ``out0``, ..."""
    return f"{direction}{index}"


def function_ref(
    text: str, base: Path, default_file: Path | None, location: SourceLocation
) -> FunctionRef:
    """Read ``file.py:function`` (or ``function`` in the accelerator's own Python source)."""
    file_text, _, name = str(text).rpartition(":")
    if not name.isidentifier():
        raise RfcError(
            f"reference '{text}' must name a Python function as 'file.py:function'",
            location=location,
        )
    if file_text:
        file = source_file(file_text, base, "reference file", location)
    elif default_file is None:
        raise RfcError(
            f"reference '{text}' names no file, and the accelerator has no Python source",
            location=location,
            hint=f"write it as 'file.py:{name}'",
        )
    else:
        file = default_file
    check_defines(file, name, f"reference '{text}'", location)
    return FunctionRef(file, name)


#: The keys of ``maxima`` besides ``fields``.
MAXIMA_KEYS = ("string", "sequence", "frame")


def maxima(
    given: dict[str, tuple[object, SourceLocation]],
    fields: dict[str, tuple[object, SourceLocation]],
) -> Limits:
    """Check the ``maxima`` of a spec: each a count a ROS length prefix can carry.

    Args:
        given: ``string``, ``sequence`` and ``frame`` as written, with their locations.
        fields: Per-field maxima by path, with their locations.
    """
    chosen = {
        what: _count(value, f"maxima '{what}'", 1 if what == "frame" else 0, location)
        for what, (value, location) in given.items()
    }
    per_field = {
        path: _count(value, f"maximum of '{path}'", 0, location)
        for path, (value, location) in fields.items()
    }
    default = Limits()
    return Limits(
        string=chosen.get("string", default.string),
        sequence=chosen.get("sequence", default.sequence),
        frame=chosen.get("frame", default.frame),
        fields=per_field,
    )


def _count(value: object, what: str, lowest: int, location: SourceLocation) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not lowest <= value < MAX_LENGTH:
        raise RfcError(
            f"{what} must be an integer from {lowest} to {MAX_LENGTH - 1}, not {value!r}",
            location=location,
        )
    return value
