"""Small YAML systems for pass tests: one subscriber per input type, chained to publishers."""

from __future__ import annotations

from pathlib import Path

from rfc.driver import compile_spec
from rfc.passes.pipeline import MODEL_PIPELINE


def compile_yaml(directory: Path, text: str):
    """Write `text` as a spec (with an accel.cpp beside it) and derive its model.

    The rules of the logic (check-hardware, with tests of its own) are left out: these specs
    exercise the passes before it, at the default maxima.
    """
    (directory / "accel.cpp").write_text("// accelerator\n")
    path = directory / "spec.yaml"
    path.write_text(text)
    return compile_spec(path, pipeline=MODEL_PIPELINE)


def pass_through(
    message: str,
    *,
    middleware: str = "ROS2",
    width: int = 64,
    include: str = "",
    publisher: str = "",
    msg_paths: str = "[]",
) -> str:
    """Subscriber → HLS pass-through accelerator → publisher, all of one message type."""
    selection = f", include: [{include}]" if include else ""
    return f"""\
project: {{name: P, middleware: {middleware}, busWidth: {width}, msg_paths: {msg_paths}}}
accelerators:
  - name: Pass
    type: HLS
    sources: ./accel.cpp
    interface: {{input: [{{message: {message}}}], output: [{{message: {message}}}]}}
blocks:
  - {{name: Sub, type: ROS>accelerator, message: {message}, outgoing: [{{name: Acc}}]}}
  - {{name: Acc, type: Pass, outgoing: [{{name: Pub{selection}}}]}}
  - {{name: Pub, type: accelerator>ROS, message: {message}{publisher}}}
"""
