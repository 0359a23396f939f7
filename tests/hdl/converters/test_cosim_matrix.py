"""Subscriber and publisher in GHDL through cocotb and cocotbext-axi, held to rosbags.

For every case of the matrix, both middlewares and the three bus widths: the subscriber must
present exactly the values rosbags deserializes (through the reference codec, itself held to
rosbags), and the publisher must send exactly the bytes rosbags serializes — with random idle
on every source and backpressure on every sink. One GHDL build per configuration serves both
converters and all its messages.
"""

from __future__ import annotations

import pytest

from rfc.lib.converters.plan import BUS_WIDTHS, plan
from rfc.messages.codec import decode, encode
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware
from rfc.toolchain import run_cocotb
from tests.hdl.converters.matrix import CASES, drawn_values, recorded
from tests.hdl.converters.pair import build_pair
from tests.hdl.converters.scenario import scenario, write_scenario

#: Room for the drawn messages (their unicode strings take up to 4 bytes a character) and
#: for the recorded ones.
LIMITS = Limits(string=255, sequence=64, frame=8192)

#: Every case at every (middleware, width) pair: 144 configurations, about 4.5 CPU-minutes.
CONFIGS = [
    pytest.param(case, middleware, width, id=f"{case.short}-{middleware.value}-{width}")
    for case in CASES
    for middleware in Middleware
    for width in BUS_WIDTHS
]


@pytest.mark.slow
@pytest.mark.parametrize(("case", "middleware", "width"), CONFIGS)
def test_converters_agree_with_rosbags(case, middleware, width, tmp_path):
    types = case.types(middleware)
    layout = flatten(types, case.type_name)
    converters = plan(layout, width, LIMITS)
    label = f"{case.short} {middleware.value} {width}-bit"
    # A few messages, fewer of the big ones: one GHDL cycle costs the same to every byte.
    count = 1 if (layout.fixed_size or 0) > 1000 else 3
    values = drawn_values(layout, label, count)
    frames = [encode(layout, v) for v in values]
    for recorded_values, frame in recorded(case, layout):
        values.append(recorded_values)
        frames.append(frame if frame is not None else encode(layout, recorded_values))
    # A recorded frame's padding may hold garbage: the publisher sends rosbags' own bytes.
    published = [encode(layout, decode(layout, frame)) for frame in frames]
    content = scenario(
        converters,
        values,
        label=label,
        seed=width,
        frames=frames,
        published=published,
    )
    files = build_pair(converters, tmp_path / "hdl")
    run_cocotb(
        files,
        "pair",
        "tests.hdl.converters.cosim_pair",
        tmp_path / "sim",
        env={"RFC_SCENARIO": str(write_scenario(tmp_path / "scenario.json", content))},
        seed=width,
    )
