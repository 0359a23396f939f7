"""The node's transports behind one interface (`DmaChannels`): how transfers reach the logic.

- ``dma``: the Linux character devices of rfc's DMA driver (`rfc.runtime.dma_device`);
- ``pynq``: the AXI DMA through PYNQ on the board (`rfc.runtime.pynq_dma`, PYNQ imported only
  there);
- ``sim``: the build's logic co-simulated in GHDL (`rfc.runtime.sim_device`).

What a user can get wrong here — a missing device, no permission, a missing bitstream or
simulator — is an `RfcError` naming the device and a way out.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from rfc.errors import RfcError
from rfc.runtime.dma_device import DmaChannels, FileDma, NoLogic
from rfc.runtime.plan import RuntimePlan


# An enum then a record, like the layout's FieldKind, the converters' SlotRole, in shape only.
class Device(StrEnum):
    """Which transport the node uses."""

    DMA = "dma"
    PYNQ = "pynq"
    SIM = "sim"


@dataclass(frozen=True)
class DeviceOptions:
    """The node's transport options (command line)."""

    device: Device = Device.DMA
    mm2s: str = ""
    s2mm: str = ""
    bitstream: str = ""
    dma: str = "axi_dma_0"


def open_transport(plan: RuntimePlan, options: DeviceOptions) -> DmaChannels:
    """Open the transport the options name (nothing moves when the system has no logic).

    Raises:
        RfcError: The device is missing or not accessible, or the transport's software is not
            installed.
    """
    if not plan.has_logic:
        return NoLogic()
    if options.device is Device.SIM:
        from rfc.runtime.sim_device import SimulatedLogic

        return SimulatedLogic.start(plan)
    if options.device is Device.PYNQ:
        from rfc.runtime.pynq_dma import PynqDma

        return PynqDma.open(options.bitstream, options.dma, plan.max_transfer)
    return open_devices(options.mm2s, options.s2mm, plan.max_transfer)


def open_devices(mm2s: str, s2mm: str, max_transfer: int) -> FileDma:
    """Open the two character devices, turning what the system refuses into an `RfcError`."""
    try:
        return FileDma.open(max_transfer, mm2s, s2mm)
    except FileNotFoundError as exc:
        raise RfcError(
            f"the DMA device {exc.filename} does not exist",
            hint="load rfc's DMA driver after the bitstream (docs/runtime.md, Deployment), "
            "or try the node on the simulated logic with --device sim",
        ) from None
    except PermissionError as exc:
        raise RfcError(
            f"no permission to open the DMA device {exc.filename}",
            hint="run the node as a user allowed to (a udev rule, or root on the board)",
        ) from None
    except OSError as exc:
        raise RfcError(f"cannot open the DMA device {exc.filename}: {exc.strerror}") from None
