"""An AXI-Stream port bundle: the five signals a stream block passes together.

The subscriber's byte window and the publisher's packer and frame buffer each take one whole
stream; the bundle names its ports once. A block binds the signals to its own local names at
elaboration (`AxiStream.signals`). That keeps the generated VHDL as it was only where the
signals are named higher up (converter ports, the converter's own signals): MyHDL declares
the signals a block names itself in the order of its parameters, so the manager's blocks, whose
streams it names, keep their ports as parameters.
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
