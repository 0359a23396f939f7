"""Reading an HLS top function's arguments: scalars, message structs and streams."""

from __future__ import annotations

import pytest

from rfc.errors import RfcError
from rfc.hls.signature import ArgumentKind, read_top_function


def test_structs_and_streams_are_read_with_their_kind_and_line(tmp_path):
    source = tmp_path / "gray.cpp"
    source.write_text(
        '#include "Gray_messages.h"\n'
        "void Gray(rgb_t rgb, hls::stream<uint8_t> &rgb_data,\n"
        "          gray_t *gray, hls::stream< uint8_t > &gray_data) {\n}\n"
    )
    arguments = read_top_function([source], "Gray")
    assert [(a.name, a.ctype, a.kind, a.output, a.location.line) for a in arguments] == [
        ("rgb", "rgb_t", ArgumentKind.STRUCT, False, 2),
        ("rgb_data", "hls::stream<uint8_t>", ArgumentKind.STREAM, True, 2),
        ("gray", "gray_t", ArgumentKind.STRUCT, True, 3),
        ("gray_data", "hls::stream<uint8_t>", ArgumentKind.STREAM, True, 3),
    ]


def test_a_scalar_convention_argument_keeps_its_width(tmp_path):
    source = tmp_path / "q.cpp"
    source.write_text("void Q(double x, uint16_t n, double *roll) {}\n")
    arguments = read_top_function([source], "Q")
    assert [(a.bits, a.kind) for a in arguments] == [
        (64, ArgumentKind.SCALAR),
        (16, ArgumentKind.SCALAR),
        (64, ArgumentKind.SCALAR),
    ]


def test_an_argument_that_is_neither_is_refused_at_its_line(tmp_path):
    source = tmp_path / "v.cpp"
    source.write_text("void V(double x,\n       std::vector<int> values) {}\n")
    with pytest.raises(RfcError) as error:
        read_top_function([source], "V")
    assert error.value.location is not None
    assert error.value.location.line == 2
