"""rfc.lib: the hardware library that generated systems are built from.

Converters, manager, schedulers and their Python models, fixed point, CORDIC, the HLS adapter
and tcl, all on plain data. Layer: beside the runtime (neither imports the other); it may import
the message layer, the toolchain and the bottom row (`rfc.cluster`, `rfc.files`,
`rfc.user_code`, `rfc.errors`), never the IR or anything that reads a spec.
"""
