"""fpgaPart: real Zynq part numbers (as Vivado lists them) pass, look-alikes are refused."""

from __future__ import annotations

import pytest

from rfc.errors import RfcError, SourceLocation
from rfc.spec.parts import fpga_family

HERE = SourceLocation("spec.yaml", 3, 13)


@pytest.mark.parametrize(
    ("part", "family"),
    [
        ("xc7z020clg400-1", "zynq"),  # PYNQ-Z1, Zybo Z7-20
        ("xc7z010clg400-1", "zynq"),  # Zybo Z7-10
        ("xc7z020clg484-1", "zynq"),  # ZedBoard
        ("xc7z045ffg900-2", "zynq"),  # ZC706
        ("xc7z007sclg225-1", "zynq"),
        ("XC7Z020CLG400-1", "zynq"),
        ("xczu9eg-ffvb1156-2-e", "zynquplus"),  # ZCU102
        ("xczu7ev-ffvc1156-2-e", "zynquplus"),  # ZCU104/106
        ("xczu3eg-sbva484-1-e", "zynquplus"),  # Ultra96
        ("xczu28dr-ffvg1517-2-e", "zynquplus"),  # ZCU111 (RFSoC)
        ("xczu5ev-sfvc784-1l-i", "zynquplus"),
    ],
)
def test_real_parts_give_their_family(part, family):
    assert fpga_family(part, HERE) == family


@pytest.mark.parametrize(
    "part",
    ["xc7z", "xc7z020", "xc7z020-fast", "xc7z999clg400-1", "xc7z020clg400", "xczu9eg",
     "xczu8eg-ffvb1156-2-e", "xczu9eg-ffvb1156-2", "xc7z020clg400-1; rm -rf /"],
)  # fmt: skip
def test_prefix_look_alikes_are_refused_with_examples(part):
    with pytest.raises(RfcError) as raised:
        fpga_family(part, HERE)
    assert raised.value.message.startswith(f"FPGA part '{part}' is not a Zynq part number")
    assert raised.value.location == HERE


def test_other_families_say_rfc_needs_a_processor():
    with pytest.raises(RfcError, match="is not a Zynq device; rfc needs a processor"):
        fpga_family("xc7a35ticsg324-1L", HERE)
