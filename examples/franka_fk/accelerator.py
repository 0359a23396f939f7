"""The forward-kinematics accelerator: a FrankaState in, its JointTransforms out.

`franka_fk` takes one interface object per message port (docs/accelerators.md): ``state``
holds the selected fields of franka_msgs/FrankaState (header, q, q_d, O_T_EE, O_T_EE_d,
F_T_EE), ``fk`` those of franka_fk_msgs/JointTransforms. It runs the resource-shared core
(`fk_core.fk_core`) twice, for q with O_T_EE and for q_d with O_T_EE_d, and keeps the input's
header. The state stays held (``state.ready`` low) until its result is taken, so the core
reads the subscriber's registers directly. The references run the core's model on rosbags
messages, bit for bit (`franka_fk_ros1`, `franka_fk_ros2`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from fk_core import fk_core, fk_model
from myhdl import Signal, always_comb, always_seq, block, intbv

from rfc.lib.converters.wiring import follow
from rfc.lib.fixed import bits_to_float, float_to_bits
from rfc.messages.rosbags_adapter import message_types

HERE = Path(__file__).resolve().parent
#: Where the messages are defined: franka_msgs beside the examples, franka_fk_msgs here.
MSG_PATHS = (str(HERE.parent / "franka" / "msg"), str(HERE / "msg"))

#: Transform entries per pass: T1…T7, 16 each.
ENTRIES = 112
_IDLE, _FIRST, _SECOND_IN, _SECOND, _DONE = range(5)


@block
def franka_fk(clk: Any, rst: Any, state: Any, fk: Any) -> Any:
    """franka_msgs/FrankaState state in, franka_fk_msgs/JointTransforms fk out."""
    second = Signal(bool(0))  # the core works on q_d and O_T_EE_d
    q = [Signal(intbv(0)[64:]) for _ in range(7)]
    o_t_ee = [Signal(intbv(0)[64:]) for _ in range(16)]
    choices = [
        choose(second, one, other, chosen)
        for one, other, chosen in zip(state.q, state.q_d, q, strict=True)
    ] + [
        choose(second, one, other, chosen)
        for one, other, chosen in zip(state.O_T_EE, state.O_T_EE_d, o_t_ee, strict=True)
    ]
    transforms = [Signal(intbv(0)[64:]) for _ in range(ENTRIES)]
    mse = Signal(intbv(0)[64:])
    start, started, done, take, first, later = (Signal(bool(0)) for _ in range(6))
    core = fk_core(clk, rst, q, state.F_T_EE, o_t_ee, start, started, transforms, mse, done, take)
    firsts = [capture(clk, rst, first, t, fk.transforms[i]) for i, t in enumerate(transforms)]
    seconds = [capture(clk, rst, later, t, fk.transforms_d[i]) for i, t in enumerate(transforms)]
    phase = Signal(intbv(_IDLE, min=0, max=5))

    @always_comb
    def handshakes() -> None:
        start.next = (phase == _IDLE and state.valid) or phase == _SECOND_IN
        take.next = phase[0]  # the phases that wait for the core, _FIRST and _SECOND, are odd
        first.next = phase == _FIRST and done
        later.next = phase == _SECOND and done
        second.next = phase >= _SECOND_IN
        fk.valid.next = phase == _DONE
        state.ready.next = phase == _DONE and fk.ready  # release the state with its result

    @always_seq(clk.posedge, reset=rst)
    def sequence() -> None:
        if phase == _IDLE and state.valid and started:
            phase.next = _FIRST
        elif phase == _FIRST and done:
            fk.mse.next = mse
            phase.next = _SECOND_IN
        elif phase == _SECOND_IN and started:
            phase.next = _SECOND
        elif phase == _SECOND and done:
            fk.mse_d.next = mse
            phase.next = _DONE
        elif phase == _DONE and fk.ready:
            phase.next = _IDLE

    header = keep_header(state.header, fk.header)
    return core, choices, firsts, seconds, handshakes, sequence, header


@block
def choose(second: Any, one: Any, other: Any, chosen: Any) -> Any:
    """`chosen` is `other` on the second pass, else `one`."""

    @always_comb
    def choose() -> None:
        chosen.next = other if second else one

    return choose


@block
def capture(clk: Any, rst: Any, load: Any, source: Any, target: Any) -> Any:
    """`target` takes `source` on the cycles `load` is high."""

    @always_seq(clk.posedge, reset=rst)
    def capture() -> None:
        if load:
            target.next = source

    return capture


@block
def keep_header(incoming: Any, outgoing: Any) -> Any:
    """The input's header, as the subscriber holds it; frame_id streams through."""
    stamp, out_stamp = incoming.stamp, outgoing.stamp
    frame, out_frame = incoming.frame_id, outgoing.frame_id
    sequence = [follow(incoming.seq, outgoing.seq)] if hasattr(incoming, "seq") else []  # ROS 1

    @always_comb
    def header() -> None:
        out_stamp.sec.next = stamp.sec
        out_stamp.nanosec.next = stamp.nanosec
        out_frame.length.next = frame.length
        out_frame.data.next = frame.data
        out_frame.valid.next = frame.valid
        frame.ready.next = out_frame.ready

    return header, sequence


def _reference(state: Any, middleware: str) -> Any:
    """The core's model on a rosbags FrankaState, bit for bit, as a JointTransforms."""
    types = message_types(middleware, msg_paths=MSG_PATHS)

    def bits(values: Any) -> list[int]:
        return [float_to_bits(float(v)) for v in values]

    def floats(patterns: Any) -> list[float]:
        return [bits_to_float(int(p)) for p in patterns]

    transforms, mse = fk_model(bits(state.q), bits(state.F_T_EE), bits(state.O_T_EE))
    transforms_d, mse_d = fk_model(bits(state.q_d), bits(state.F_T_EE), bits(state.O_T_EE_d))
    stamp = {"sec": state.header.stamp.sec, "nanosec": state.header.stamp.nanosec}
    header = {"stamp": stamp, "frame_id": state.header.frame_id}
    if hasattr(state.header, "seq"):
        header["seq"] = state.header.seq
    return types.build(
        "franka_fk_msgs/msg/JointTransforms",
        {
            "header": header,
            "transforms": floats(transforms),
            "transforms_d": floats(transforms_d),
            "mse": bits_to_float(int(mse)),
            "mse_d": bits_to_float(int(mse_d)),
        },
    )


def franka_fk_ros1(state: Any) -> Any:
    """The reference of the ROS 1 system (franka_ros publishes ROS 1)."""
    return _reference(state, "ros1")


def franka_fk_ros2(state: Any) -> Any:
    """The reference of the ROS 2 system."""
    return _reference(state, "ros2")
