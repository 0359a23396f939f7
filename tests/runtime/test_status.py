"""The logic's drop counters read through the status chunk (docs/protocol.md)."""

from __future__ import annotations

import json
import random
import struct
from collections import Counter
from pathlib import Path

import pytest

from rfc.lib.converters.malformed import DROP_REASONS
from rfc.lib.manager.header import STATUS_ID as HARDWARE_STATUS_ID
from rfc.messages.rosbags_adapter import message_types, read_bag, write_bag
from rfc.runtime.protocol import STATUS_ID, ProtocolError
from rfc.runtime.status import STATUS_REASONS, decode_status, is_status, status_request
from tests.cli.test_sim_malformed import POINT, spec_text
from tests.lower.system.systems import PASS_THROUGH, write_spec
from tests.support.cli import run_rfc

ROOT = Path(__file__).resolve().parents[2]


def test_the_runtime_reads_the_counters_in_the_order_the_logic_sends_them():
    assert tuple(r.label for r in DROP_REASONS) == STATUS_REASONS
    assert STATUS_ID == HARDWARE_STATUS_ID


def test_an_answer_decodes_by_subscriber_then_reason():
    values = list(range(100, 108))
    answer = struct.pack("<HHI", 0xFFFF, 3, 32) + struct.pack("<8I", *values)
    assert is_status(answer)
    assert not is_status(struct.pack("<HHI", 1, 3, 0))
    assert status_request().to_bytes() == struct.pack("<HHI", 0xFFFF, 3, 0)
    counts = decode_status(answer, [1, 0])
    assert counts[(0, "truncated")] == 100
    assert counts[(0, "encoding")] == 103
    assert counts[(1, "maximum")] == 105
    with pytest.raises(ProtocolError, match="not the 48 bytes of 3 subscribers"):
        decode_status(answer, [0, 1, 2])


def test_rfc_sim_reads_each_kind_of_drop_exactly_through_the_status_chunk(tmp_path):
    """A Point system in GHDL: the account's counts are the frames sent of each kind."""
    rng = random.Random(15)
    types = message_types("ros2")
    spec = write_spec(tmp_path, spec_text("ROS2", 32, POINT), pass__py=PASS_THROUGH)
    valid = [
        types.serialize(types.build(POINT, {"x": rng.random(), "y": -1.5, "z": 2.0**i}), POINT)
        for i in range(12)
    ]
    kinds = ["valid"] * 5 + ["truncated"] * 3 + ["trailing"] * 2 + ["encoding"] * 2
    rng.shuffle(kinds)
    frames, expected = [], []
    for kind, frame in zip(kinds, valid, strict=True):
        if kind == "truncated":
            frame = frame[: rng.randrange(1, len(frame))]
        elif kind == "trailing":
            frame += rng.randbytes(rng.randrange(1, 12))
        elif kind == "encoding":
            frame = b"\x00\x00" + frame[2:]  # big-endian CDR
        else:
            expected.append(frame)
        frames.append(frame)
    bag = tmp_path / "in.mcap"
    write_bag(bag, types, {"/in": POINT}, [("/in", 1000 * i, f) for i, f in enumerate(frames)])
    out = tmp_path / "out.mcap"
    result = run_rfc(
        "sim", spec, "--bag", bag, "--out", out, "--send-malformed", "--simulator", "ghdl",
        "--json", cwd=ROOT,
    )  # fmt: skip
    assert result.returncode == 0, result.stderr
    account = json.loads(result.stdout)
    assert [m.data for m in read_bag(out, types)] == expected
    dropped = Counter({(d["where"], d["reason"]): d["count"] for d in account["dropped"]})
    sent = Counter(("sub", f"logic:{kind}") for kind in kinds if kind != "valid")
    assert dropped == sent
