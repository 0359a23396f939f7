"""The image pipeline at full-HD maxima fits the xc7z020's block RAM.

The spec's maxima allow 1920x1080 rgb8 images (6,220,800 bytes of ``data``). The subscriber's
guard holds only the bytes before ``data``; the stages are record-first, so the publisher keeps
FIFOs for ``frame_id`` and ``encoding`` only and streams the pixels through.
"""

from __future__ import annotations

import re

from rfc.lib.devices import block_rams
from tests.examples.image_pipeline.example import EXAMPLE
from tests.support.cli import run_rfc

FULL_HD = 1920 * 1080 * 3


def test_the_full_hd_spec_passes_rfc_check():
    assert f"data: {FULL_HD}}}" in (EXAMPLE / "ImagePipeline.yaml").read_text()
    result = run_rfc("check", EXAMPLE / "ImagePipeline.yaml", cwd=EXAMPLE)
    assert result.returncode == 0, result.stderr


def test_the_full_hd_build_buffers_only_the_short_strings_and_the_prefix(tmp_path):
    result = run_rfc("build", EXAMPLE / "ImagePipeline.yaml", "-o", tmp_path / "b", cwd=EXAMPLE)
    assert result.returncode == 0, result.stderr
    report = (tmp_path / "b" / "report.md").read_text()
    rows = re.findall(r"^\| `(\w+)` \| `([^`]+)` \| (\d+) \| (\d+) \| [\d.]+ \| (\d+) \|$", report,
                      re.MULTILINE)  # fmt: skip
    held = {(block, path) for block, path, *_ in rows}
    assert held == {
        ("Integral_pub", "header.frame_id"),
        ("Integral_pub", "encoding"),
        ("Camera_sub", "(frame before 'data')"),
    }
    # a string of at most 64 characters in beats of 8 bytes
    assert [int(words) for block, _, words, _, _ in rows if block == "Integral_pub"] == [8, 8]
    have, _ = block_rams("xc7z020clg400-1")
    assert sum(int(brams) for *_, brams in rows) <= have
