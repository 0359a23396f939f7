"""rfc.hls: the interface between an HLS accelerator's C++ top function and its messages.

The top function as read from its sources (`rfc.hls.signature`), the message structs and
streams it takes (`rfc.hls.c_types`) and the Vitis core's ports they become (`rfc.hls.ports`).
The hardware check and the lowering read the same facts here, so a core the check accepts is
the core the lowering wires.

Layer: beside the front-ends, below the passes; it imports the IR, the hardware library and
the errors only.
"""
