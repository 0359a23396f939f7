"""Register slices in the top level: no handshake runs from one block straight into another.

Built from the image pipeline example (strings and sequences between a subscriber, three stages
and a publisher) and the quaternion example (fixed-size messages), the top level is read back
instance by instance: every sub-stream's `tvalid` a block takes from another comes out of a
slice, and the `tready` it gives back goes into that slice; a fixed-size message's handshake
likewise.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.lower.system.systems import PASS_THROUGH, fan_out, write_spec
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[3]
INSTANCE = re.compile(r"^  (\w+) : entity work\.(\w+)\n    port map \((.*?)\);", re.M | re.S)


def instances(top: Path) -> dict[str, tuple[str, dict[str, str]]]:
    """Each cell of a generated top level: label → (entity, port → net)."""
    cells = {}
    for label, entity, body in INSTANCE.findall(top.read_text()):
        pairs = (line.strip().rstrip(",").split(" => ") for line in body.strip().splitlines())
        cells[label] = (entity, dict(pairs))
    return cells


@pytest.mark.parametrize(
    ("spec", "top", "handshake", "consumers"),
    [
        # the sub-streams; a streamed message's record (fields, lengths, msg_valid) is direct
        # the publisher streams `data` through, record-first: it takes it straight
        ("image_pipeline/ImagePipeline.yaml", "image_pipeline_pl", "t", 3),
        ("quaternion_to_euler/project.yaml", "quaternion_to_euler_pl", "", 2),
    ],
)
def test_every_handshake_between_blocks_crosses_a_slice(tmp_path, spec, top, handshake, consumers):
    out = tmp_path / "build"
    result = run_rfc("build", ROOT / "examples" / spec, "-o", out, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    assert sliced_consumers(out / "hw" / f"{top}.vhd", handshake) == consumers


def test_each_block_a_message_fans_out_to_takes_it_from_a_slice(tmp_path):
    # the fork shares the message: its outputs go into a slice per consumer, as one consumer's
    spec = write_spec(tmp_path, fan_out(), pass__py=PASS_THROUGH)
    result = run_rfc("build", spec, "-o", tmp_path / "build", cwd=ROOT)
    assert result.returncode == 0, result.stderr
    # first, second and their two publishers
    assert sliced_consumers(tmp_path / "build" / "hw" / "fan_out_pl.vhd", "") == 4


def sliced_consumers(top: Path, handshake: str) -> int:
    """How many blocks take a message or sub-stream; asserts each takes it from a slice."""
    cells = instances(top)
    slices = {label for label, (entity, _) in cells.items() if re.search(r"_slice\d+$", entity)}
    from_slice = {cells[s][1]["m_valid"] for s in slices}
    into_slice = {cells[s][1]["m_ready"] for s in slices}
    # a busy watch only looks at handshakes (for rfc sim's end of replay): it takes no message
    watches = {label for label, (entity, _) in cells.items() if re.search(r"_busy\d+x\d+$", entity)}
    guarded = set()
    for label, (_, ports) in cells.items():
        if label in slices or label in watches or label in ("manager", "integral_pub"):
            continue
        for port, net in ports.items():
            taken = port.endswith(f"_{handshake}valid") and net != f"{label}_{port}"
            if port.startswith(("m_axis", "s_axis", "s_valid")) or not taken:
                continue  # the DMA side, a subscriber's gate, or a handshake the block gives
            # a message or sub-stream this block takes: valid from a slice, ready into it
            assert net in from_slice, f"{label}.{port} takes {net} straight from a block"
            ready = ports[port.removesuffix(f"{handshake}valid") + f"{handshake}ready"]
            assert ready in into_slice, f"{label} gives {ready} straight to a block"
            guarded.add(label)
    return len(guarded)
