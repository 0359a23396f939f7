"""The DMA on a Zynq running Linux, as the ROS 2 node sees it: one character device per channel.

The kernel driver interface rfc expects (docs/runtime.md, "Deployment"):

- ``/dev/rfc_mm2s`` (PS→PL): each ``write()`` of a buffer is one DMA transfer, ended with
  ``tlast``; the call blocks until the DMA has taken the whole buffer and returns its length.
- ``/dev/rfc_s2mm`` (PL→PS): each ``read()`` returns exactly one DMA transfer (up to ``tlast``),
  blocking until one has arrived; the buffer passed must hold the largest transfer, otherwise
  the driver fails the read with ``EMSGSIZE`` and drops that transfer.

This is the transfer-per-call behaviour of character-device wrappers around the Xilinx AXI DMA
engine (such as Xilinx's dma-proxy example driver with a read/write front). A Unix
``SOCK_SEQPACKET`` socket pair keeps message boundaries the same way, which is how the tests
stand in for the logic.
"""

from __future__ import annotations

import contextlib
import os
from dataclasses import dataclass
from typing import Protocol

#: Device paths of the two channels.
MM2S_DEVICE = "/dev/rfc_mm2s"
S2MM_DEVICE = "/dev/rfc_s2mm"


class DmaChannels(Protocol):
    """The two DMA channels: one transfer per call in each direction."""

    def write(self, transfer: bytes) -> None:
        """Send one PS→PL transfer; blocks until the DMA took it."""
        ...

    def read(self) -> bytes:
        """Receive one PL→PS transfer; blocks until one arrives (b"" once closed)."""
        ...

    def close(self) -> None:
        """Release the channels (a blocked `read` then returns b"")."""
        ...


@dataclass
class FileDma:
    """`DmaChannels` over two file descriptors (character devices, or a socket pair's ends).

    Args:
        mm2s: Descriptor written for PS→PL transfers.
        s2mm: Descriptor read for PL→PS transfers.
        max_transfer: Size of the read buffer: the largest PL→PS transfer.
    """

    mm2s: int
    s2mm: int
    max_transfer: int

    @classmethod
    def open(cls, max_transfer: int, mm2s: str = MM2S_DEVICE, s2mm: str = S2MM_DEVICE) -> FileDma:
        """Open the two character devices."""
        return cls(os.open(mm2s, os.O_WRONLY), os.open(s2mm, os.O_RDONLY), max_transfer)

    def write(self, transfer: bytes) -> None:
        """One write per transfer; a short write would cut the chunk, so it is an error."""
        written = os.write(self.mm2s, transfer)
        if written != len(transfer):
            raise OSError(f"DMA took {written} of {len(transfer)} bytes of one transfer")

    def read(self) -> bytes:
        """One read per transfer."""
        return os.read(self.s2mm, self.max_transfer)

    def close(self) -> None:
        """Close both descriptors (once)."""
        for descriptor in {self.mm2s, self.s2mm}:
            with contextlib.suppress(OSError):
                os.close(descriptor)


class NoLogic:
    """`DmaChannels` of a system without logic (every accelerator in software): nothing moves."""

    def write(self, transfer: bytes) -> None:
        """Never called: no subscriber is in the logic."""
        raise OSError("this system has no logic to send to")

    def read(self) -> bytes:
        """Nothing ever arrives."""
        return b""

    def close(self) -> None:
        """Nothing to release."""
