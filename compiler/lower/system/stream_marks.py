"""Keep and last for sub-streams that go from one accelerator straight into another.

An accelerator's output sub-stream has no ``tkeep`` or ``tlast`` (a publisher reads neither);
an accelerator's input has both (a subscriber gives them). Where a connection joins the two,
`StreamMarks` puts a `rfc.lib.converters.stream_marks` cell beside the stream that derives them
from its length, so the consumer sees the stream exactly as a subscriber would give it.
"""

from __future__ import annotations

from pathlib import Path

from rfc.ir.model import Connection, Design
from rfc.lib.converters.plan import plan
from rfc.lib.converters.steps import Payload
from rfc.lib.converters.stream_marks import marks_ports, stream_marks
from rfc.lower.system.components import Component, convert
from rfc.lower.system.top import Interface, Terminal, TopBuilder
from rfc.messages.limits import Limits

#: The pins a consumer needs that only a subscriber gives, by suffix.
MARKS = ("_tkeep", "_tlast")


class StreamMarks:
    """The marks cells of a system's accelerator-to-accelerator streams, and their components.

    Args:
        prefix: The project's identifier, which the components' names start with.
        width: Bus width in bits.
        directory: Where the VHDL goes.
        limits: The maxima the ports are built for.
    """

    def __init__(self, prefix: str, width: int, directory: Path, limits: Limits) -> None:
        self.prefix, self.width, self.directory, self.limits = prefix, width, directory, limits
        self.components: list[Component] = []
        self._kinds: dict[tuple[int, int, int], Component] = {}

    def complete(
        self,
        builder: TopBuilder,
        design: Design,
        connection: Connection,
        source: Interface,
        destination: Interface,
    ) -> Interface:
        """`source` with the keep and last pins `destination` needs and it lacks."""
        groups = sorted(
            {
                name.removesuffix(suffix)
                for name in destination
                for suffix in MARKS
                if name.endswith(suffix) and name not in source
            }
        )
        if not groups:
            return source
        sizes = self._element_sizes(design, connection)
        completed = dict(source)
        for group in groups:
            if group not in sizes or f"{group}_length" not in source:
                continue  # an element channel's last: wire_connection names what is missing
            length = source[f"{group}_length"]
            keep_bits = builder.port(destination[f"{group}_tkeep"]).bits
            component = self._component(builder.port(length).bits, keep_bits, sizes[group])
            cell = f"{destination[f'{group}_tvalid'].cell}_{group}_marks"
            builder.cell(cell, component.entity)
            builder.wire(length, Terminal(cell, "length"))
            builder.wire(source[f"{group}_tvalid"], Terminal(cell, "tvalid"))
            builder.wire(destination[f"{group}_tready"], Terminal(cell, "tready"))
            completed[f"{group}_tkeep"] = Terminal(cell, "tkeep")
            completed[f"{group}_tlast"] = Terminal(cell, "tlast")
        return completed

    def _element_sizes(self, design: Design, connection: Connection) -> dict[str, int]:
        """Bytes per element of each sub-stream of the connection's destination port."""
        port = design.block(connection.destination.block).port(connection.destination.port or "")
        assert port.layout is not None
        steps = plan(port.layout, self.width, self.limits).steps
        return {s.stream: s.element_size for s in steps if isinstance(s, Payload) and s.stream}

    def _component(self, length_bits: int, beat: int, element_size: int) -> Component:
        key = (length_bits, beat, element_size)
        if key not in self._kinds:
            name = f"{self.prefix}_marks{len(self._kinds)}"
            what = "keep and last of an accelerator's sub-stream (rfc)"
            ports = marks_ports(length_bits, beat)
            self._kinds[key] = convert(
                name, ports, stream_marks, self.directory, what, element_size=element_size
            )
            self.components.append(self._kinds[key])
        return self._kinds[key]
