"""An AXI-Stream port bundle: the five signals a stream block passes together.

The subscriber's byte window, the publisher's packer and frame buffer, and the manager's
demultiplexer, multiplexer and status inserter each take whole streams; the bundle names its
ports once. A block binds the signals to its own local names at elaboration
(`AxiStream.signals`), so its processes read ``s_tdata`` and the like as before. Converted as
the top level, a block's bundle parameter ``s`` gives the ports ``s_tdata`` … ``s_tlast``.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from rfc.lib.types import SignalLike

#: A stream's signals, by the suffix of their ports' names.
STREAM = ("tdata", "tkeep", "tvalid", "tready", "tlast")


@dataclass(frozen=True)
class AxiStream:
    """The signals of one AXI-Stream interface; their widths are the block's to define.

    Attributes:
        tdata: Beat data (lane 0 in the low byte).
        tkeep: Byte enables.
        tvalid: The beat is valid.
        tready: The consumer takes the beat.
        tlast: The last beat of a frame.
    """

    tdata: SignalLike
    tkeep: SignalLike
    tvalid: SignalLike
    tready: SignalLike
    tlast: SignalLike

    @classmethod
    def named(cls, ports: Mapping[str, SignalLike], bus: str) -> AxiStream:
        """The stream of `ports` ``<bus>_tdata`` … ``<bus>_tlast``."""
        return cls(*(ports[f"{bus}_{name}"] for name in STREAM))

    def signals(self) -> tuple[SignalLike, SignalLike, SignalLike, SignalLike, SignalLike]:
        """tdata, tkeep, tvalid, tready, tlast: to bind to a block's local names."""
        return self.tdata, self.tkeep, self.tvalid, self.tready, self.tlast
