"""The image stages in MyHDL's simulator, against NumPy: every pixel, header and size.

Images of varying size go through one stage back to back — odd widths and heights, one row,
one column, images that downscale to nothing — with idle cycles on the input and random
back-pressure on every output.
"""

from __future__ import annotations

import numpy as np
import pytest

from rfc.lib.arith import dot_product
from tests.examples.image_pipeline.example import example_module

stages = example_module("stages")
reference = example_module("image_reference")
bench = example_module("image_bench")
FRAME, random_pictures, run_stage = bench.FRAME, bench.random_pictures, bench.run_stage

SIZES = [(5, 7), (1, 1), (2, 2), (1, 9), (8, 1), (30, 40), (13, 17), (3, 2), (0, 0), (16, 24)]
WITH_ENCODING = bench.WITH_ENCODING


def check(results, pictures, expected, encoding=None, pixel_bytes=1):
    assert len(results) == len(pictures)
    for picture, result, want in zip(pictures, results, expected, strict=True):
        assert (result.height, result.width) == want.shape
        assert result.data == want.tobytes()
        assert (result.sec, result.nanosec, result.frame_id) == (
            picture.sec,
            picture.nanosec,
            picture.frame_id,
        )
        if encoding is not None:
            assert result.encoding == encoding
            assert result.step == pixel_bytes * want.shape[1]


STAGES = {
    "RgbToGray: OpenCV's integer luma": ("rgb_to_gray", "gray", 3, "mono8", 1),
    "Downscale: the rounded mean of each 2x2 block": ("downscale", "downscale", 1, "mono8", 1),
    "IntegralImage: cumulative sums as little-endian uint32": (
        "integral_image", "integral", 1, "32SC1", 4),
}  # fmt: skip


@pytest.mark.parametrize("width", [32, 64])
@pytest.mark.parametrize("stage", STAGES.values(), ids=STAGES.keys())
def test_each_stage_gives_numpys_image_with_the_input_header(stage, width):
    block, formula, channels, encoding, pixel_bytes = stage
    pictures = random_pictures(np.random.default_rng(width + channels), SIZES, channels)
    results = run_stage(getattr(stages, block), pictures, WITH_ENCODING, width, seed=width)
    expected = [getattr(reference, formula)(p.pixels) for p in pictures]
    check(results, pictures, expected, encoding, pixel_bytes)


def test_rgb_to_grays_dot_product_is_opencvs_luma_for_every_colour():
    """The stage's block computes `dot_product` (tests/lib/arith/test_dot.py): its weights and
    format must give OpenCV's integer luma on all 2**24 colours, none saturated."""
    red, green = (c.ravel() for c in np.meshgrid(np.arange(256), np.arange(256)))
    for blue in range(256):
        rgb = np.stack([red, green, np.full_like(red, blue)], axis=-1)
        got = dot_product([red, green, rgb[:, 2]], stages.GRAY_WEIGHTS, stages.LUMA)
        assert np.array_equal(got, reference.gray(rgb))


def test_a_stage_whose_output_has_no_encoding_sends_only_the_frame():
    pictures = random_pictures(np.random.default_rng(5), [(4, 6), (3, 3)], channels=1)
    results = run_stage(stages.integral_image, pictures, FRAME, 64)
    assert [r.encoding for r in results] == [None, None]
    check(results, pictures, [reference.integral(p.pixels) for p in pictures])


def test_bright_images_sum_beyond_sixteen_bits():
    pictures = random_pictures(np.random.default_rng(6), [(30, 40)], channels=1)
    white = [type(pictures[0])(np.full((30, 40), 255, np.uint8), 1, 2, "white")]
    results = run_stage(stages.integral_image, white, FRAME, 64)
    assert np.frombuffer(results[0].data, "<u4")[-1] == 255 * 30 * 40


def test_the_three_stages_joined_as_the_top_level_joins_them_give_numpys_pipeline():
    pictures = random_pictures(np.random.default_rng(7), SIZES[:6], channels=3)
    run = bench.run_chain(
        [stages.rgb_to_gray, stages.downscale, stages.integral_image],
        pictures,
        WITH_ENCODING,
        traffic=bench.Traffic(),
        seed=7,
    )
    expected = [reference.pipeline(p.pixels) for p in pictures]
    check(run.results, pictures, expected, "32SC1", pixel_bytes=4)
