"""Block RAM of the target devices, for the publishers' buffers.

A buffer holds one message's strings and sequences at the project's maxima, so maxima left at
their defaults can ask for more memory than any Zynq has; rfc refuses such a logic at build
time, naming the largest buffer, instead of generating what cannot be placed (or simulated:
GHDL would allocate it too).
"""

from __future__ import annotations

import math
import re

#: 36 Kb block RAMs of the Zynq-7000 devices (DS190), by the part's device name.
ZYNQ_7000_BRAM36 = {
    "xc7z007s": 50,
    "xc7z010": 60,
    "xc7z012s": 72,
    "xc7z014s": 107,
    "xc7z015": 95,
    "xc7z020": 140,
    "xc7z030": 265,
    "xc7z035": 500,
    "xc7z045": 545,
    "xc7z100": 755,
}
#: For parts not in the table: about the block and UltraRAM of the largest Zynq UltraScale+.
OTHER_PART_BRAM36 = 2048

#: Block RAM 36 Kb aspect ratios of the 7 series (width, depth), parity bits used as data.
_BRAM36 = ((72, 512), (36, 1024), (18, 2048), (9, 4096), (4, 8192), (2, 16384), (1, 32768))


def bram36(bits: int, words: int) -> int:
    """The fewest 36 Kb block RAMs a memory of `words` words of `bits` fits in."""
    return min(math.ceil(bits / w) * math.ceil(words / d) for w, d in _BRAM36)


def block_rams(part: str) -> tuple[int, bool]:
    """The 36 Kb block RAMs of `part`, and whether the figure is the device's own."""
    match = re.match(r"xc7z\d+s?", part.lower())
    if match and match[0] in ZYNQ_7000_BRAM36:
        return ZYNQ_7000_BRAM36[match[0]], True
    return OTHER_PART_BRAM36, False
