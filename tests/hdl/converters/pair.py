"""A test top holding a plan's subscriber and publisher side by side (not connected).

One GHDL build then serves both converters of a configuration: the subscriber's ports are
prefixed ``sub_``, the publisher's ``pub_``; clock and reset are shared.
"""

from __future__ import annotations

import warnings
from pathlib import Path

from myhdl import ToVerilogWarning, ToVHDLWarning, block

from rfc.lib.converters.ports import Side, dma_ports, ports_of
from rfc.lib.converters.publisher import rfc_publisher
from rfc.lib.converters.steps import Plan
from rfc.lib.converters.subscriber import rfc_subscriber
from rfc.lib.converters.toplevel import port_signals, top_block
from rfc.toolchain import convert_myhdl, elaboration

SHARED = ("clk", "rst")


def _ports(plan: Plan, side: Side) -> list:
    return [p for p in (*dma_ports(plan, side), *ports_of(plan, side)) if p.name not in SHARED]


@block
def converter_pair(plan: Plan, **ports):
    shared = {name: ports[name] for name in SHARED}
    sub = {p.name: ports[f"sub_{p.name}"] for p in _ports(plan, Side.SUBSCRIBER)}
    pub = {p.name: ports[f"pub_{p.name}"] for p in _ports(plan, Side.PUBLISHER)}
    subscriber = rfc_subscriber(plan, **shared, **sub)
    publisher = rfc_publisher(plan, **shared, **pub)
    return subscriber, publisher


def build_pair(plan: Plan, directory: Path, name: str = "pair") -> list[Path]:
    """Convert the pair to VHDL in `directory`; return the files in compile order."""
    ports = [p for p in dma_ports(plan, Side.SUBSCRIBER) if p.name in SHARED]
    signals = port_signals(ports)
    for side, prefix in ((Side.SUBSCRIBER, "sub_"), (Side.PUBLISHER, "pub_")):
        for port, signal in port_signals(_ports(plan, side)).items():
            signals[prefix + port] = signal
    with elaboration(), warnings.catch_warnings():
        warnings.simplefilter("ignore", ToVHDLWarning)
        warnings.simplefilter("ignore", ToVerilogWarning)
        top = top_block(name, list(signals), converter_pair, plan=plan)
        files = convert_myhdl(top(**signals), name, directory, verilog=False)
    return files
