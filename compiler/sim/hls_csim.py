"""HLS accelerators C-simulated on the processor side of ``rfc sim``, without vendor tools.

`rfc sim` moves HLS accelerators to the processor (`HlsOnProcessor`, a pass in front of the
pipeline) and runs each as a ROS-SW accelerator whose function is a `CSimulation`: the top
function compiled by the system's g++ with rfc's generated header
(`rfc.hls.c_types`), a generated harness (`rfc.lower.hls_harness`, which documents the
binary format on the pipe) and rfc's own ``hls_stream.h`` (``rfc/lib/hls/include``). A build is
compiled once and kept by the hash of everything that goes into it.
"""

from __future__ import annotations

import hashlib
import os
import re
import struct
import subprocess
import tempfile
import weakref
from collections.abc import Mapping
from dataclasses import dataclass, replace
from importlib import resources
from pathlib import Path
from typing import IO, Any, ClassVar

import numpy as np

from rfc.errors import RfcError, SourceLocation
from rfc.hls.c_types import CStream, MessageStruct, hls_header, message_structs
from rfc.hls.signature import ArgumentKind, HlsArgument, read_top_function
from rfc.ir.model import AcceleratorKind, AcceleratorType, Design
from rfc.lower.hls_harness import hls_harness
from rfc.lower.hls_headers import first_block, port_signatures
from rfc.messages.codec import default_values
from rfc.messages.layout import Layout
from rfc.messages.rosbags_adapter import MessageTypes
from rfc.messages.values import message_to_values, values_to_message
from rfc.passes.base import types_of

#: How g++ compiles a C simulation.
CXXFLAGS = ("-std=c++14", "-O2")
#: `struct` formats of the C types on the pipe.
_FORMATS = {
    "bool": "?",
    "char": "B",
    "float": "f",
    "double": "d",
    **{f"int{b}_t": f for b, f in ((8, "b"), (16, "h"), (32, "i"), (64, "q"))},
    **{f"uint{b}_t": f.upper() for b, f in ((8, "b"), (16, "h"), (32, "i"), (64, "q"))},
}
_GXX_ERROR = re.compile(r"^(?P<file>[^:\n]+):(?P<line>\d+):(?P<column>\d+): error: (?P<what>.+)$")


@dataclass(frozen=True)
class HlsOnProcessor:
    """Run HLS accelerators as processor-side functions (their C simulation) in ``rfc sim``."""

    name: ClassVar[str] = "hls-on-processor"

    def apply(self, design: Design) -> Design:
        """Turn each HLS accelerator type into a ROS-SW one awaiting its C simulation."""
        return replace(
            design,
            accelerators=tuple(
                replace(
                    a, kind=AcceleratorKind.ROS_SW, reference=None, reference_function=_Pending()
                )
                if a.kind is AcceleratorKind.HLS
                else a
                for a in design.accelerators
            ),
        )


class _Pending:
    """Stands for a C simulation until `attach_c_simulations` compiles it."""

    def __call__(self, *messages: object) -> Any:
        raise AssertionError("attach_c_simulations was not called")


def attach_c_simulations(design: Design, cache: Path | None = None) -> Design:
    """Compile the C simulation of every HLS accelerator `HlsOnProcessor` moved.

    Args:
        design: The holistic model, from a pipeline that starts with `HlsOnProcessor`.
        cache: Where compiled harnesses are kept (default: ``$XDG_CACHE_HOME/rfc/hls-csim``).

    Raises:
        RfcError: The top function does not take the generated structs, or g++ refused it.
    """
    cache = cache or default_cache()
    types = types_of(design.project)
    accelerators = []
    for accelerator in design.accelerators:
        block = first_block(design, accelerator)
        if isinstance(accelerator.reference_function, _Pending) and block is not None:
            signatures, directions = port_signatures(design, block)
            layouts = {p.name: p.layout for p in block.ports if p.layout is not None}
            top = accelerator.top or accelerator.name
            structs = message_structs(signatures, directions)
            header = hls_header(accelerator.name, structs, top)
            function = CSimulation.build(accelerator, structs, header, layouts, types, cache)
            accelerator = replace(accelerator, reference_function=function)
        accelerators.append(accelerator)
    return replace(design, accelerators=tuple(accelerators))


def default_cache() -> Path:
    """The directory compiled C simulations are kept in."""
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "rfc" / "hls-csim"


class CSimulation:
    """An HLS accelerator's compiled C simulation, called like a ROS-SW function.

    The harness process starts at the first call and serves every call after it.

    Args:
        name: The accelerator type.
        program: The compiled harness.
        structs: Its ports' structs.
        layouts: Its ports' layouts (selected fields).
        types: The message definitions (to build output messages).
    """

    def __init__(
        self,
        name: str,
        program: Path,
        structs: tuple[MessageStruct, ...],
        layouts: Mapping[str, Layout],
        types: MessageTypes,
    ) -> None:
        self.name = name
        self.program = program
        self.inputs = tuple(s for s in structs if not s.output)
        self.outputs = tuple(s for s in structs if s.output)
        self.layouts = layouts
        self.types = types
        self._process: subprocess.Popen[bytes] | None = None
        self._said: IO[bytes] | None = None

    @classmethod
    def build(
        cls,
        accelerator: AcceleratorType,
        structs: tuple[MessageStruct, ...],
        header: str,
        layouts: Mapping[str, Layout],
        types: MessageTypes,
        cache: Path,
    ) -> CSimulation:
        """Check the top function against the structs and compile it (or reuse a build).

        Raises:
            RfcError: The top function's arguments are not the structs' (or the fields'), or
                g++ refused the sources.
        """
        top = accelerator.top or accelerator.name
        sources = [p for p in accelerator.sources if p.suffix in _SOURCES]
        arguments = read_top_function(sources, top)
        scalars = arguments if _check_arguments(accelerator, top, arguments, structs) else ()
        files = {
            f"{accelerator.name}_messages.h": header,
            f"{accelerator.name}_harness.cpp": hls_harness(accelerator.name, top, structs, scalars),
        }
        program = _compile(accelerator, files, sources, cache)
        return cls(accelerator.name, program, structs, layouts, types)

    def __call__(self, *messages: object) -> Any:
        """Run the top function on one message per input; one message per output.

        Raises:
            RfcError: The C simulation stopped, or wrote streams unlike their lengths.
        """
        request = bytearray(b"\x01")
        for port, message in zip(self.inputs, messages, strict=True):
            request += _encode(port, message_to_values(message, self.layouts[port.port]))
        process = self._started()
        assert process.stdin is not None
        assert process.stdout is not None
        try:
            process.stdin.write(request)
            process.stdin.flush()
            results = [self._decode(port, process.stdout) for port in self.outputs]
        except (BrokenPipeError, EOFError):
            raise self._failure() from None
        return results[0] if len(results) == 1 else tuple(results)

    def _started(self) -> subprocess.Popen[bytes]:
        if self._process is None:
            self._said = tempfile.TemporaryFile()  # noqa: SIM115 (lives as long as the process)
            self._process = subprocess.Popen(
                [str(self.program)],
                stdin=subprocess.PIPE,
                stdout=subprocess.PIPE,
                stderr=self._said,
            )
            weakref.finalize(self, _stop, self._process)
        return self._process

    def _failure(self) -> RfcError:
        assert self._process is not None
        assert self._said is not None
        self._process.wait()
        self._said.seek(0)
        said = self._said.read().decode(errors="replace").strip()[-2000:]
        return RfcError(
            f"the C simulation of HLS accelerator '{self.name}' stopped "
            f"(exit status {self._process.returncode}): {said or 'no message'}",
            hint="a top function reads every element of its input streams and no more",
        )

    def _decode(self, port: MessageStruct, pipe: IO[bytes]) -> object:
        layout = self.layouts[port.port]
        values = default_values(layout)
        lengths = {}
        for field in port.fields:
            value = _read(pipe, field.ctype)
            if field.length:
                lengths[field.path] = value
            else:
                values[field.path] = value
        for stream in port.streams:
            (count,) = struct.unpack("<I", _exactly(pipe, 4))
            elements = _read_elements(pipe, stream, count)
            if count != lengths[stream.path]:
                raise RfcError(
                    f"HLS accelerator '{self.name}' wrote {count} elements on stream "
                    f"{stream.argument} but set {port.port}->{stream.length.access[1:]} to "
                    f"{lengths[stream.path]}",
                    hint="set each stream's length field to the number of elements written",
                )
            values[stream.path] = _stream_value(stream, elements, layout)
        return values_to_message(values, layout, self.types)


_SOURCES = (".cpp", ".cc", ".cxx", ".c")


def _stop(process: subprocess.Popen[bytes]) -> None:
    if process.poll() is None:
        if process.stdin is not None:
            process.stdin.close()
        process.wait()


def _check_arguments(
    accelerator: AcceleratorType,
    top: str,
    arguments: tuple[HlsArgument, ...],
    structs: tuple[MessageStruct, ...],
) -> bool:
    """Whether the top function takes scalars; check its arguments are what the ports give.

    Raises:
        RfcError: They are not, naming the first argument at fault.
    """
    scalar = all(a.kind is ArgumentKind.SCALAR for a in arguments)
    expected = []
    if scalar and not any(s.streams for s in structs):  # scalars cannot carry streams
        expected = [
            (ArgumentKind.SCALAR, f.ctype, s.output, f"{s.port}{f.access}".replace(".", "_"))
            for s in structs
            for f in s.fields
        ]
    if not expected:
        for s in structs:
            expected.append((ArgumentKind.STRUCT, s.type_name, s.output, s.port))
            expected += [
                (ArgumentKind.STREAM, f"hls::stream<{t.element}>", True, t.argument)
                for t in s.streams
            ]
    wanted = ", ".join(
        f"{ctype} {'&' if kind is ArgumentKind.STREAM else '*' if output else ''}{name}"
        for kind, ctype, output, name in expected
    )
    hint = f"declare it as void {top}({wanted}) (docs/accelerators.md, HLS accelerators)"
    if len(arguments) != len(expected):
        raise RfcError(
            f"HLS top function {top} of accelerator '{accelerator.name}' has "
            f"{len(arguments)} arguments; its messages give {len(expected)}",
            location=arguments[0].location if arguments else accelerator.location,
            hint=hint,
        )
    for argument, (kind, ctype, output, name) in zip(arguments, expected, strict=True):
        same = argument.kind is kind and argument.output == output
        if kind is ArgumentKind.SCALAR:
            same = same and argument.bits == _SCALAR_BITS[ctype]
        else:
            same = same and argument.ctype == ctype
        if not same:
            raise RfcError(
                f"argument '{argument.name}' of HLS top function {top} is "
                f"{_mode(argument.output)} {argument.ctype}; expected {_mode(output)} {ctype} "
                f"for {name}",
                location=argument.location,
                hint=hint,
            )
    return bool(expected) and expected[0][0] is ArgumentKind.SCALAR


def _mode(output: bool) -> str:
    return "an output" if output else "an input"


_SCALAR_BITS = {"bool": 1, "char": 8, "float": 32, "double": 64} | {
    f"{s}int{b}_t": b for s in ("", "u") for b in (8, 16, 32, 64)
}


def _compile(
    accelerator: AcceleratorType, files: Mapping[str, str], sources: list[Path], cache: Path
) -> Path:
    """The harness program, compiled unless the cache holds a build of the same inputs."""
    include = resources.files("rfc.lib").joinpath("hls/include")
    digest = hashlib.sha256()
    for part in (*CXXFLAGS, *files.values(), Path(str(include), "hls_stream.h").read_text()):
        digest.update(part.encode() + b"\0")
    for source in sources:
        digest.update(str(source).encode() + b"\0" + source.read_bytes() + b"\0")
    folder = cache / f"{accelerator.name}-{digest.hexdigest()[:16]}"
    program = folder / accelerator.name
    if program.exists():
        return program
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in files.items():
        (folder / name).write_text(text)
    harness = folder / f"{accelerator.name}_harness.cpp"
    directories = dict.fromkeys([folder, Path(str(include)), *(s.parent for s in sources)])
    partial = folder / f".{accelerator.name}.{os.getpid()}"
    command = [
        "g++",
        *CXXFLAGS,
        *(f"-I{d}" for d in directories),
        str(harness),
        *map(str, sources),
        "-o",
        str(partial),
    ]
    try:
        done = subprocess.run(command, capture_output=True, text=True, check=False)
    except FileNotFoundError:
        raise RfcError(
            "C simulation of HLS accelerators needs g++, which is not on the PATH",
            hint="install g++ (Debian: apt-get install g++)",
        ) from None
    if done.returncode != 0:
        raise _compile_error(accelerator, done.stderr)
    partial.replace(program)
    return program


def _compile_error(accelerator: AcceleratorType, output: str) -> RfcError:
    first = next((m for m in map(_GXX_ERROR.match, output.splitlines()) if m), None)
    location = accelerator.location
    what = output.strip().splitlines()[-1] if output.strip() else "no message"
    if first is not None:
        location = SourceLocation(first["file"], int(first["line"]), int(first["column"]))
        what = first["what"]
    return RfcError(
        f"g++ cannot compile HLS accelerator '{accelerator.name}' for C simulation: {what}",
        location=location,
        hint=f"its sources include {accelerator.name}_messages.h, which rfc generates "
        f"(`rfc stub SPEC {accelerator.name} --lang hls` shows it); g++ said:\n"
        + "\n".join(output.strip().splitlines()[:12]),
    )


def _encode(port: MessageStruct, values: Mapping[str, Any]) -> bytes:
    out = bytearray()
    for field in port.fields:
        value = len(_sequence(values[field.path])) if field.length else values[field.path]
        out += struct.pack("<" + _FORMATS[field.ctype], value)
    for stream in port.streams:
        value = values[stream.path]
        if stream.fields:
            for element in value:
                for field in stream.fields:
                    out += struct.pack("<" + _FORMATS[field.ctype], element[field.path])
        else:
            out += np.asarray(_sequence(value)).astype("<" + _FORMATS[stream.element]).tobytes()
    return bytes(out)


def _sequence(value: Any) -> Any:
    """A stream's elements: a string's UTF-8 bytes as a byte array."""
    return np.frombuffer(value.encode(), np.uint8) if isinstance(value, str) else value


def _exactly(pipe: IO[bytes], size: int) -> bytes:
    data = pipe.read(size)
    if len(data) != size:
        raise EOFError
    return data


def _read(pipe: IO[bytes], ctype: str) -> Any:
    code = "<" + _FORMATS[ctype]
    return struct.unpack(code, _exactly(pipe, struct.calcsize(code)))[0]


def _read_elements(pipe: IO[bytes], stream: CStream, count: int) -> Any:
    if stream.fields:
        return [{f.path: _read(pipe, f.ctype) for f in stream.fields} for _ in range(count)]
    dtype = np.dtype("<" + _FORMATS[stream.element])
    return np.frombuffer(_exactly(pipe, dtype.itemsize * count), dtype)


def _stream_value(stream: CStream, elements: Any, layout: Layout) -> Any:
    """The field value of a stream's elements, as `values_to_message` takes it."""
    field = next(f for f in layout.fields if f.path == stream.path)
    if stream.fields:
        assert field.element is not None
        return [default_values(field.element) | element for element in elements]
    if stream.element == "char":
        return bytes(elements).decode(errors="replace")
    return np.array(elements)
