"""Run a bag's messages through a generated subscriber→publisher loopback in simulation.

Every message of one type is parsed by the subscriber and serialized again by the publisher,
in one of three readings of the same logic: the RTL VHDL in GHDL, GHDL's synthesized netlist of
it in GHDL, or rfc's Verilog in Verilator;
each frame that comes out is compared with rosbags' serialization of rosbags' deserialization
of the recorded frame (recorded padding may hold garbage, so the recorded bytes themselves are
not the reference). Limits are fitted to the bag's messages, so the hardware is as small as the
data allows and the loopback's FIFOs hold a whole message. This is what ``rfc msg loopback``
runs.
"""

from __future__ import annotations

import tempfile
import warnings
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from myhdl import ToVerilogWarning, ToVHDLWarning

from rfc.errors import RfcError, did_you_mean
from rfc.lib.converters.loopback import LOOPBACK, loopback_ports, rfc_loopback
from rfc.lib.converters.plan import plan
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.toplevel import port_signals, top_block
from rfc.messages.codec import FrameError, Values, decode, default_values
from rfc.messages.layout import FieldKind, Layout, flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import (
    BagMessage,
    MessageTypes,
    Middleware,
    canonical_name,
    message_types,
    read_bag,
    skipped_topics,
)
from rfc.messages.selection import select
from rfc.messages.values import message_to_values, values_to_message
from rfc.toolchain import GhdlError, convert_myhdl, elaboration, simulate, synthesize_vhdl
from rfc.toolchain.verilator import VerilatorError, run_testbench

TESTBENCH = Path(__file__).parent / "hdl" / "loopback_tb.vhd"
VERILOG_TESTBENCH = Path(__file__).parent / "hdl" / "loopback_tb.v"


@dataclass(frozen=True)
class LoopbackResult:
    """One message through the loopback.

    Attributes:
        index: Position among the bag's messages of the type (from 0).
        equal: Whether the publisher sent exactly rosbags' bytes.
        subscriber_cycles: From the first beat into the subscriber to its fields valid.
        publisher_cycles: From the fields given to the publisher to its last beat out.
    """

    index: int
    equal: bool
    subscriber_cycles: int
    publisher_cycles: int


# Like rfc.toolchain's VhdlEntity in shape only: a run's results.
@dataclass(frozen=True)
class LoopbackReport:
    """All messages of a type through the loopback (its JSON: docs/architecture.md)."""

    type_name: str
    middleware: Middleware
    width: int
    results: tuple[LoopbackResult, ...]
    skipped: tuple[str, ...] = ()
    """Topics of the bag left out as services or actions (``topic (type)``)."""

    @property
    def equal(self) -> bool:
        """Whether every message came out byte-exact."""
        return all(result.equal for result in self.results)

    def as_json(self) -> dict[str, Any]:
        """The document ``rfc msg loopback --json`` prints."""
        return {
            "type": self.type_name,
            "middleware": self.middleware.value,
            "width": self.width,
            "messages": len(self.results),
            "equal": self.equal,
            "results": [
                {
                    "index": r.index,
                    "equal": r.equal,
                    "subscriber_cycles": r.subscriber_cycles,
                    "publisher_cycles": r.publisher_cycles,
                }
                for r in self.results
            ],
        }


def recorded_middleware(bag: Path) -> Middleware:
    """ROS 1 for a ``.bag`` file, ROS 2 (CDR) otherwise (``.mcap``, ``.db3``, folders)."""
    return Middleware.ROS1 if bag.suffix == ".bag" else Middleware.ROS2


def loopback(
    type_name: str,
    bag: Path,
    *,
    topic: str | None = None,
    middleware: Middleware | None = None,
    width: int = 64,
    count: int | None = None,
    workdir: Path | None = None,
    msg_paths: Sequence[Path] = (),
    include: Sequence[str] = (),
    exclude: Sequence[str] = (),
    simulator: str = "ghdl",
    netlist: bool = False,
) -> LoopbackReport:
    """Stream the bag's messages of `type_name` through a subscriber→publisher loopback.

    Args:
        type_name: The message type (definitions also come from the bag).
        bag: A ROS 1 or ROS 2 bag.
        topic: Only messages of this topic.
        middleware: The bag's middleware; taken from the file when omitted.
        width: Bus width in bits.
        count: Only the first `count` messages.
        workdir: Keep the generated HDL and simulation files here (a temporary folder
            otherwise).
        msg_paths: Directories of definitions the bag does not embed.
        include: Only these fields go through the accelerator side (dotted paths).
        exclude: These fields do not; the publisher sends their defaults, and the expected
            frames have them too.
        simulator: ``ghdl`` or ``verilator``.
        netlist: Simulate GHDL's synthesized netlist of the loopback instead of its VHDL (in
            GHDL).

    Returns:
        One result per message.

    Raises:
        RfcError: The bag, type or topic is unknown, the bag holds no such message, or the
            middleware does not match the bag.
    """
    recorded = recorded_middleware(bag)
    if middleware is not None and middleware is not recorded:
        raise RfcError(
            f"bag '{bag}' was recorded with {recorded.label}, not {middleware.label}",
            hint=f"use --middleware {recorded.value} or leave it out",
        )
    types = message_types(recorded, None, tuple(str(p) for p in msg_paths), (str(bag),))
    canonical = types.resolve(type_name)
    messages = _messages(bag, types, canonical, topic, count)
    layout = select(flatten(types, canonical), include, exclude)
    values = [_decoded(layout, m) for m in messages]
    longest_frame = max(len(m.data) for m in messages)
    converters = plan(layout, width, fitted_limits(layout, values, longest_frame))
    if workdir is not None:
        report = _run(converters, types, messages, workdir, simulator, netlist)
    else:
        with tempfile.TemporaryDirectory(prefix="rfc-loopback-") as scratch:
            report = _run(converters, types, messages, Path(scratch), simulator, netlist)
    return replace(report, skipped=skipped_topics(bag))


def _messages(
    bag: Path, types: MessageTypes, canonical: str, topic: str | None, count: int | None
) -> list[BagMessage]:
    found: list[BagMessage] = []
    present = set()
    for message in read_bag(bag, types, [topic] if topic else ()):
        name = canonical_name(message.type_name)  # other types need no definition
        present.add(types.display_name(name))
        if name == canonical and (count is None or len(found) < count):
            found.append(message)
    if not found:
        wanted = types.display_name(canonical)
        where = f"topic '{topic}' of bag '{bag}'" if topic else f"bag '{bag}'"
        if not present:
            raise RfcError(
                f"{where} holds no messages at all", hint="record some, or give another bag"
            )
        raise RfcError(
            f"{where} has no message of type {wanted}",
            hint=did_you_mean(wanted, present) or f"it has {', '.join(sorted(present))}",
        )
    return found


def _decoded(layout: Layout, message: BagMessage) -> dict[str, Any]:
    try:
        return decode(layout, message.data)
    except FrameError as error:
        raise RfcError(
            f"a recorded {layout.display_name} message on {message.topic} is not valid: {error}"
        ) from None


def fitted_limits(layout: Layout, messages: Sequence[Mapping[str, Any]], frame: int) -> Limits:
    """Limits just large enough for these messages, whose longest frame has `frame` bytes."""
    longest: dict[str, int] = {}
    for values in messages:
        for path, length in _lengths(layout, values, ""):
            longest[path] = max(longest.get(path, 1), length)
    return Limits(string=1, sequence=1, frame=frame, fields=longest)


def _lengths(layout: Layout, values: Mapping[str, Any], prefix: str) -> Iterator[tuple[str, int]]:
    for leaf in layout.fields:
        path = prefix + leaf.path
        value = values[leaf.path]
        if leaf.kind is FieldKind.STRING:
            yield path, len(value.encode())
        elif leaf.element is not None:
            yield path, len(value)
            for item in value:
                yield from _lengths(leaf.element, item, path + ".")
        elif leaf.element_type == "string":
            yield path, len(value)
            for text in value:
                yield path + "[]", len(text.encode())
        elif leaf.kind is FieldKind.SEQUENCE:
            yield path, len(value)


# Fields and values derived from them, like rfc.dse.metrics' Summary in shape only: cycle marks.
@dataclass(frozen=True)
class FrameTiming:
    """When one frame passed the loopback's points (cycles), and its beats on each bus.

    Attributes:
        first_in: The subscriber took the frame's first beat.
        last_in: The subscriber took its last beat.
        fields: The subscriber presented the message's fields (the publisher got them).
        first_out: The publisher sent the first beat.
        last_out: The publisher sent the last beat.
        beats_in: Beats the subscriber took.
        beats_out: Beats the publisher sent.
    """

    first_in: int
    last_in: int
    fields: int
    first_out: int
    last_out: int
    beats_in: int
    beats_out: int

    @property
    def subscriber_cycles(self) -> int:
        """Latency from the first beat in to the fields valid."""
        return self.fields - self.first_in

    @property
    def publisher_cycles(self) -> int:
        """Latency from the fields given to the last beat out (the cycle of the last beat too)."""
        return self.last_out - self.fields + 1

    @property
    def subscriber_throughput(self) -> float:
        """Beats per cycle while the subscriber took the frame (the source never idles)."""
        return self.beats_in / (self.last_in - self.first_in + 1)

    @property
    def publisher_throughput(self) -> float:
        """Beats per cycle while the publisher sent the frame (the sink never stalls)."""
        return self.beats_out / (self.last_out - self.first_out + 1)


def run_frames(
    converters: Plan,
    frames: Sequence[bytes],
    workdir: Path,
    simulator: str = "ghdl",
    netlist: bool = False,
) -> list[tuple[bytes, FrameTiming]]:
    """Send frames through the plan's loopback in GHDL or Verilator, one in flight at a time.

    The source sends every beat as soon as the subscriber takes it and the sink never stalls,
    so the timings are the converters' own.

    Args:
        converters: The plan of both converters.
        frames: Frames for the subscriber.
        workdir: The generated HDL and the simulation's files go here.
        simulator: ``ghdl`` (the VHDL and loopback_tb.vhd) or ``verilator`` (the Verilog and
            loopback_tb.v, the same events on the same cycles).
        netlist: In GHDL, simulate GHDL's synthesized netlist of the loopback
            (``rfc_loopback_netlist.vhd``) instead of its VHDL.

    Returns:
        What the publisher sent for each frame, with its timing, in order; shorter than
        `frames` when the loopback stopped moving (a hardware bug).

    Raises:
        RfcError: The simulation did not run, or GHDL could not synthesize the loopback.
    """
    width = converters.width
    workdir = workdir.resolve()  # GHDL runs elsewhere: a relative path would point astray
    workdir.mkdir(parents=True, exist_ok=True)
    with elaboration(), warnings.catch_warnings():
        warnings.simplefilter("ignore", ToVHDLWarning)
        warnings.simplefilter("ignore", ToVerilogWarning)
        ports = loopback_ports(width)
        top = top_block(LOOPBACK, [p.name for p in ports], rfc_loopback, plan=converters)
        verilog = simulator == "verilator"
        files = convert_myhdl(top(**port_signals(ports)), LOOPBACK, workdir, verilog=verilog)
    source = workdir / "frames.txt"
    source.write_text("".join(_beats(frame, width) for frame in frames))
    events = workdir / "events.txt"
    try:
        if verilog:
            run_testbench(
                [files[-1], VERILOG_TESTBENCH],
                "rfc_loopback_tb",
                {"WIDTH": width},
                {"input": str(source), "output": str(events)},
                workdir / "verilator",
            )
        else:
            sources = [files[0], _netlist(files, workdir)] if netlist else files
            simulate(
                [*sources, TESTBENCH],
                "rfc_loopback_tb",
                workdir / "work",
                {"WIDTH": width, "INPUT_FILE": source, "OUTPUT_FILE": events},
            )
    except (GhdlError, VerilatorError) as error:
        raise RfcError(f"the loopback simulation failed: {error}") from None
    beats_in = [-(-len(frame) // width) for frame in frames]
    return list(_outputs(events, width, beats_in))


def _netlist(files: Sequence[Path], workdir: Path) -> Path:
    """GHDL's synthesized netlist of the loopback's VHDL: same entity, same ports.

    It still uses MyHDL's package, the first of `files`.

    Raises:
        GhdlError: GHDL cannot synthesize it.
    """
    netlist = workdir / f"{LOOPBACK}_netlist.vhd"
    netlist.write_text(synthesize_vhdl(files, LOOPBACK, workdir / "synth"))
    return netlist


def _run(
    converters: Plan,
    types: MessageTypes,
    messages: list[BagMessage],
    workdir: Path,
    simulator: str,
    netlist: bool,
) -> LoopbackReport:
    outputs = run_frames(converters, [m.data for m in messages], workdir, simulator, netlist)
    canonical = converters.layout.type_name
    results = []
    layout = converters.layout
    for index, (message, (sent, timing)) in enumerate(zip(messages, outputs, strict=False)):
        # A recorded frame's padding may hold garbage: the reference is rosbags' own bytes,
        # with the fields left out of the selection at their defaults.
        received = types.deserialize(message.data, canonical)
        if any(not field.selected for field in layout.fields):
            values = _selected_only(layout, message_to_values(received, layout))
            received = values_to_message(values, layout, types)
        expected = types.serialize(received, canonical)
        results.append(
            LoopbackResult(
                index, sent == expected, timing.subscriber_cycles, timing.publisher_cycles
            )
        )
    results += [LoopbackResult(i, False, 0, 0) for i in range(len(results), len(messages))]
    return LoopbackReport(
        layout.display_name, layout.middleware, 8 * converters.width, tuple(results)
    )


def _selected_only(layout: Layout, values: Values) -> Values:
    """The values with every leaf outside the selection at its default (as a publisher sends)."""
    defaults = default_values(layout)
    kept: Values = {}
    for field in layout.fields:
        value = values[field.path] if field.selected else defaults[field.path]
        if field.selected and field.element is not None:
            value = [_selected_only(field.element, item) for item in value]
        kept[field.path] = value
    return kept


def _beats(frame: bytes, width: int) -> str:
    lines = []
    for start in range(0, len(frame), width):
        beat = frame[start : start + width]
        last = int(start + width >= len(frame))
        lines.append(f"{last} {len(beat)} {int.from_bytes(beat, 'little'):0{2 * width}X}\n")
    return "".join(lines)


def _outputs(
    events: Path, width: int, beats_in: Sequence[int]
) -> Iterator[tuple[bytes, FrameTiming]]:
    """Each frame the publisher sent, with its timing (see the testbench's header)."""
    frame = bytearray()
    marks: dict[str, int] = {}
    beats_out = sent = 0
    for line in events.read_text().splitlines():
        word, *rest = line.split()
        if word in ("start", "last", "fields"):
            marks[word] = int(rest[0])
        elif word == "beat":
            if beats_out == 0:
                marks["first_out"] = int(rest[0])
            beats_out += 1
            keep, data = int(rest[2], 16), int(rest[3], 16).to_bytes(width, "little")
            frame += bytes(b for lane, b in enumerate(data) if keep >> lane & 1)
        elif word == "end":
            yield (
                bytes(frame),
                FrameTiming(
                    marks["start"],
                    marks["last"],
                    marks["fields"],
                    marks["first_out"],
                    int(rest[0]),
                    beats_in[sent],
                    beats_out,
                ),
            )
            frame.clear()
            marks.clear()
            beats_out = 0
            sent += 1
        elif word == "stall":
            return
