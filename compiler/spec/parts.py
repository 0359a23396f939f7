"""Xilinx Zynq part numbers: the devices rfc targets, read as Vivado spells them.

A part is a device, a package and a speed grade. rfc accepts the Zynq-7000 devices of DS190
(``xc7z020`` + package such as ``clg400`` + ``-1``, e.g. ``xc7z020clg400-1``) and the Zynq
UltraScale+ MPSoC/RFSoC devices of DS891/DS889 (``xczu9eg`` + ``-ffvb1156`` + ``-2`` +
``-e``, e.g. ``xczu9eg-ffvb1156-2-e``), case-insensitively. A part that only shares a prefix with
these (``xc7z999``, ``xczu3eg-anything``) is refused before Vivado would be.
"""

from __future__ import annotations

import re

from rfc.errors import RfcError, SourceLocation, did_you_mean

#: Zynq-7000 devices (DS190).
ZYNQ_7000 = ("007s", "010", "012s", "014s", "015", "020", "030", "035", "045", "100")
#: Zynq UltraScale+ devices: MPSoC CG/EG/EV (DS891) and RFSoC DR (DS889).
ZYNQ_ULTRASCALE_PLUS = (
    *(f"{n}cg" for n in (1, 2, 3, 4, 5, 6, 7, 9)),
    *(f"{n}eg" for n in (1, 2, 3, 4, 5, 6, 7, 9, 11, 15, 17, 19)),
    *(f"{n}ev" for n in (4, 5, 7)),
    "3tcg",
    "3teg",
    *(f"{n}dr" for n in (21, 25, 27, 28, 29, 39, 42, 43, 46, 47, 48, 49, 65, 67)),
)
_ZYNQ_7000 = re.compile(rf"xc7z({'|'.join(ZYNQ_7000)})[a-z]{{3}}\d{{3,4}}-[123][a-z]?")
_ULTRASCALE_PLUS = re.compile(
    rf"xczu({'|'.join(ZYNQ_ULTRASCALE_PLUS)})-[a-z]{{4}}\d{{3,4}}-[123](l|lv|le)?-[eiq]"
)
#: Examples shown when a part is refused.
EXAMPLES = ("xc7z020clg400-1", "xc7z010clg400-1", "xczu3eg-sbva484-1-e", "xczu9eg-ffvb1156-2-e")


def fpga_family(part: str, location: SourceLocation) -> str:
    """The Vivado family of a Zynq part number (``zynq`` or ``zynquplus``).

    Raises:
        RfcError: `part` is not a Zynq part number of the documented form.
    """
    lowered = part.strip().lower()
    if _ZYNQ_7000.fullmatch(lowered):
        return "zynq"
    if _ULTRASCALE_PLUS.fullmatch(lowered):
        return "zynquplus"
    if not lowered.startswith(("xc7z", "xczu")):
        raise RfcError(
            f"FPGA part '{part}' is not a Zynq device; rfc needs a processor beside the logic",
            location=location,
            hint="use a Zynq-7000 (xc7z...) or Zynq UltraScale+ (xczu...) part, "
            "such as xc7z020clg400-1",
        )
    raise RfcError(
        f"FPGA part '{part}' is not a Zynq part number: expected a device, package and speed "
        "grade as Vivado names them (xc7z020clg400-1, xczu9eg-ffvb1156-2-e)",
        location=location,
        hint=did_you_mean(lowered, EXAMPLES) or f"for example {', '.join(EXAMPLES)}",
    )
