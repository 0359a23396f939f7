"""The IR's YAML writer, held to ruamel.yaml's reading of what it writes."""

from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st
from ruamel.yaml import YAML

from rfc.ir.yaml_text import Flow, dump_yaml, scalar

TRICKY = [
    "y",
    "yes",
    "No",
    "null",
    "~",
    "true",
    "1.5",
    "0x1F",
    ".inf",
    "-",
    "a: b",
    "a #b",
    "[x]",
    "{x}",
    "pose.covariance[35]",
    "ROS>accelerator",
    "/imu/data",
    "",
    " lead",
    "trail ",
    "quote'd",
    'dq"',
    "tab\tin",
    "new\nline",
    "ünï",
    "\u2028",
    "@at",
    "!bang",
    "%pct",
    "*star",
    "&amp",
    "|pipe",
    ">fold",
    "`tick",
    "a, b",
    "?q",
    "x:y",
]

scalars = (
    st.none()
    | st.booleans()
    | st.integers(-(2**70), 2**70)
    | st.floats(allow_nan=False, allow_infinity=False)
    | st.text(max_size=12)
    | st.sampled_from(TRICKY)
)
keys = st.text(max_size=8) | st.sampled_from(TRICKY)
leaves = st.dictionaries(keys, scalars, max_size=4).map(Flow) | scalars
documents = st.recursive(
    leaves,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(keys, inner, max_size=4),
    max_leaves=25,
)


def read(text):
    return YAML(typ="safe", pure=True).load(text)


@given(st.dictionaries(keys, documents, max_size=5))
def test_what_is_written_reads_back_unchanged(document):
    assert read(dump_yaml(document)) == document


def test_plain_where_plain_is_safe_quoted_otherwise():
    assert scalar("geometry_msgs/msg/Quaternion") == "geometry_msgs/msg/Quaternion"
    assert scalar("ROS>accelerator") == "ROS>accelerator"
    assert scalar("yes") == '"yes"'
    assert scalar("pose.covariance[35]") == '"pose.covariance[35]"'
    assert scalar(None) == "null"
    assert scalar(1.0e-6) == "1e-06"


def test_layout_rows_are_one_line_each():
    text = dump_yaml({"fields": [Flow(path="x", bits=64), Flow(path="y", bits=64)]})
    assert text == "fields:\n  - {path: x, bits: 64}\n  - {path: y, bits: 64}\n"
