"""The elaboration context: fast, reproducible MyHDL conversion that nobody else can observe."""

from __future__ import annotations

import inspect
import os
import subprocess
import sys
import threading
from pathlib import Path

import myhdl._block
import myhdl._instance
import myhdl._visitors
import myhdl.conversion._analyze
import pytest

from rfc.toolchain import elaboration

CONVERT_ONE = """
import sys
import threading
from pathlib import Path
from rfc.lib.converters.build import generate
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Side
from rfc.messages.layout import flatten
from rfc.messages.limits import Limits
from rfc.messages.rosbags_adapter import Middleware, message_types
layout = flatten(message_types(Middleware.ROS2), "sensor_msgs/msg/JointState")
generate(plan(layout, 32, Limits()), Side.PUBLISHER, Path(sys.argv[1]))
"""


def _untouched() -> bool:
    return (
        myhdl._block.inspect is inspect
        and myhdl._instance.inspect is inspect
        and "set" not in vars(myhdl._visitors)
        and "set" not in vars(myhdl.conversion._analyze)
    )


def test_same_design_same_bytes_in_every_process(tmp_path: Path) -> None:
    """Two processes with different string hashes write byte-identical VHDL and Verilog."""
    outputs = []
    for seed in ("1", "2"):
        directory = tmp_path / seed
        environment = {**os.environ, "PYTHONHASHSEED": seed}
        subprocess.run(
            [sys.executable, "-c", CONVERT_ONE, str(directory)], check=True, env=environment
        )
        outputs.append({f.name: f.read_bytes() for f in sorted(directory.iterdir())})
    assert outputs[0].keys() == outputs[1].keys()
    assert {".vhd", ".v"} <= {Path(name).suffix for name in outputs[0]}
    assert outputs[0] == outputs[1]


def test_inspect_itself_is_never_replaced() -> None:
    """Inside the context only MyHDL's modules see the quick stack; on exit all is restored."""
    standard_stack = inspect.stack
    with elaboration():
        assert inspect.stack is standard_stack
        assert inspect.stack()[0].code_context is not None  # the standard one, with source
        assert myhdl._block.inspect.stack()[0].code_context is None
        assert myhdl._block.inspect.getsource is inspect.getsource
    assert _untouched()


def _fail_inside_nested_contexts() -> None:
    with elaboration():
        with elaboration():
            pass
        assert not _untouched()  # the outer context is still in force
        raise RuntimeError("the user's block failed")


def test_restored_after_an_error_and_when_nested() -> None:
    with pytest.raises(RuntimeError, match="user's block"):
        _fail_inside_nested_contexts()
    assert _untouched()


def test_threads_elaborate_one_at_a_time_and_leave_nothing_behind() -> None:
    """Two threads in the context at once (a Dask worker pool does this) restore MyHDL whole."""
    inside = threading.Barrier(2, timeout=1)
    overlapped = []

    def elaborate() -> None:
        with elaboration():
            try:
                inside.wait()  # both inside at once only if the contexts overlap
                overlapped.append(True)
            except threading.BrokenBarrierError:
                overlapped.append(False)

    threads = [threading.Thread(target=elaborate) for _ in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert overlapped == [False, False]
    assert _untouched()
