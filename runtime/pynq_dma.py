"""The AXI DMA through PYNQ: the bitstream loaded as an overlay, one transfer per call.

PYNQ runs on the board only, so it is imported when this transport opens. Buffers are
physically contiguous (``pynq.allocate``): a write copies the transfer into the send buffer and
waits for the MM2S channel; a read waits for one S2MM transfer (the DMA ends it at ``tlast``)
and returns the bytes it wrote.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rfc.errors import RfcError


@dataclass
class PynqDma:
    """`DmaChannels` over a PYNQ AXI DMA.

    Args:
        dma: The overlay's AXI DMA driver.
        send: Contiguous buffer of the PS→PL channel.
        receive: Contiguous buffer of the PL→PS channel (the largest transfer).
    """

    dma: Any
    send: Any
    receive: Any
    closed: bool = False

    @classmethod
    def open(cls, bitstream: str, dma_name: str, max_transfer: int) -> PynqDma:
        """Load the bitstream and find its DMA.

        Raises:
            RfcError: PYNQ is not installed, no bitstream was given, or it has no such DMA.
        """
        try:
            import numpy as np
            import pynq
        except ImportError:
            raise RfcError(
                "--device pynq needs PYNQ, which is not installed here",
                hint="run the node on a PYNQ board (pip install pynq), or use --device dma",
            ) from None
        if not bitstream:
            raise RfcError(
                "--device pynq needs the bitstream", hint="pass --bitstream BUILD/system.bit"
            )
        try:
            overlay = pynq.Overlay(bitstream)
        except (OSError, ValueError, RuntimeError) as exc:
            raise RfcError(f"cannot load the bitstream {bitstream}: {exc}") from None
        dma = getattr(overlay, dma_name, None)
        if dma is None:
            raise RfcError(
                f"the bitstream {bitstream} has no AXI DMA called '{dma_name}'",
                hint="name it with --dma, as the block design calls it",
            )
        send = pynq.allocate(shape=(max_transfer,), dtype=np.uint8)
        receive = pynq.allocate(shape=(max_transfer,), dtype=np.uint8)
        return cls(dma, send, receive)

    def write(self, transfer: bytes) -> None:
        """Send one transfer and wait until the DMA took it."""
        self.send[: len(transfer)] = memoryview(transfer)
        self.dma.sendchannel.transfer(self.send, nbytes=len(transfer))
        self.dma.sendchannel.wait()

    def read(self) -> bytes:
        """Wait for one transfer (b"" once closed)."""
        if self.closed:
            return b""
        self.dma.recvchannel.transfer(self.receive)
        self.dma.recvchannel.wait()
        return bytes(self.receive[: self.dma.recvchannel.transferred])

    def close(self) -> None:
        """Free the buffers."""
        self.closed = True
        self.send.freebuffer()
        self.receive.freebuffer()
