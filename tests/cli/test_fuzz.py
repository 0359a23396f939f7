"""Property-based test of the command line: no traceback, no hang, no broken VHDL accepted.

Bounded for the suite (well under 60 s); tools/fuzz_cli.py runs the same cases for longer.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from tests.support.cli_fuzz import build_analyses, listing_1_copy, mutated_spec, run


def _explain(outcome) -> str:
    return f"rfc {' '.join(outcome.args)} -> {outcome.status} {outcome.escaped}\n{outcome.stderr}"


@settings(max_examples=80)
@given(mutated_spec())
def test_mutated_specs_are_checked_without_a_traceback(case):
    suffix, text = case
    with tempfile.TemporaryDirectory() as work:
        listing_1_copy(Path(work))
        (Path(work) / f"spec.{suffix}").write_text(text)
        outcome = run(["check", f"spec.{suffix}"], Path(work))
    assert outcome.handled, _explain(outcome)


@settings(max_examples=6)
@given(mutated_spec())
def test_a_mutated_spec_that_builds_gives_vhdl_ghdl_analyses(case):
    suffix, text = case
    with tempfile.TemporaryDirectory() as work:
        listing_1_copy(Path(work))
        (Path(work) / f"spec.{suffix}").write_text(text)
        outcome = run(["build", f"spec.{suffix}", "-o", "out"], Path(work), fresh=True)
        assert outcome.handled, _explain(outcome)
        if outcome.status == 0:
            assert build_analyses(Path(work) / "out") is None


@settings(max_examples=15)
@given(
    st.binary(max_size=2048),
    st.sampled_from(
        [
            ("check", "x.yaml"),
            ("check", "x.py"),
            ("build", "RotationConverterNode.yaml", "-o", "x.mcap"),
            ("sim", "RotationConverterNode.yaml", "--bag", "x.bag", "--out", "o.bag"),
            ("msg", "show", "geometry_msgs/msg/Point", "--bag", "x.mcap"),
        ]
    ),
)
def test_random_bytes_as_spec_source_or_bag_are_one_message(data, args):
    with tempfile.TemporaryDirectory() as work:
        listing_1_copy(Path(work))
        for name in ("x.yaml", "x.py", "x.bag", "x.mcap"):
            (Path(work) / name).write_bytes(data)
        (Path(work) / "QuaternionToEulerConverter.cpp").write_bytes(data)
        outcome = run(list(args), Path(work), fresh=args[0] == "build")
    assert outcome.handled, _explain(outcome)
    assert outcome.status != 0 or args[0] == "build"  # random bytes are never a valid spec/bag


@settings(max_examples=15)
@given(
    st.sampled_from(["--depth", "--drain-cycles", "--stall-cycles", "--seed", "--queue"]),
    st.one_of(st.integers(-(2**70), 2**70).map(str), st.sampled_from(["", "x", "nan", "1e9"])),
)
def test_random_option_values_are_handled(option, value):
    with tempfile.TemporaryDirectory() as work:
        listing_1_copy(Path(work))
        args = ["sim", "RotationConverterNode.yaml", "--bag", "none.bag", "--out", "o.bag"]
        outcome = run([*args, option, value], Path(work))
    assert outcome.handled, _explain(outcome)
