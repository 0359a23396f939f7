"""Arithmetic for MyHDL accelerators: sine/cosine, multiply, multiply-accumulate and more.

Also pipelined float64 ↔ fixed converters and a resource-shared engine for transform products.

Each block has a bit-exact Python model beside it (`sincos`, `mac`, `engine`); the MyHDL blocks
live in the `*_hdl` modules.
"""

from rfc.lib.arith.dot import dot_latency, dot_product
from rfc.lib.arith.sincos import SinCosConfig, sincos

__all__ = ["SinCosConfig", "dot_latency", "dot_product", "sincos"]
