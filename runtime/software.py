"""ROS-SW accelerators: a Python function run on rosbags message objects (the software fallback).

Calling convention (docs/runtime.md): the function takes one rosbags message object per input
port, positionally in the order the accelerator declares its inputs, and returns, for one output
port, a message object or None (no message this time); for several, a tuple with one entry per
output port in declaration order (None where it sends nothing), or a dict of port name to
message.

Which function: the accelerator's Python reference when it names one (so that a hardware
accelerator switched to ROS-SW runs its reference model, with nothing else changed in the
spec), else ``top`` in its Python source, else a function named like the accelerator type in
its Python source.

An accelerator with several inputs fires when every input has received a message since it last
fired, on the newest message of each; a message replaced by a newer one before that is counted
as superseded.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from rfc.errors import RfcError
from rfc.ir.model import AcceleratorType, Block
from rfc.spec.python_sources import function_in

_ROLE = "ROS-SW accelerator"

Function = Callable[..., Any]


def load_function(accelerator: AcceleratorType) -> Function:
    """Find the Python function a ROS-SW accelerator runs.

    Raises:
        RfcError: No Python source or reference names a function, or it does not exist.
    """
    if accelerator.reference_function is not None:
        return accelerator.reference_function
    if accelerator.reference is not None:
        return function_in(
            accelerator.reference.file, accelerator.reference.name, accelerator, _ROLE
        )
    python = next((p for p in accelerator.sources if p.suffix == ".py"), None)
    if python is None:
        raise RfcError(
            f"accelerator '{accelerator.name}' runs as ROS-SW but has neither a Python "
            "reference nor a Python source to run",
            location=accelerator.location,
            hint="name its Python model with 'reference: file.py:function'",
        )
    return function_in(python, accelerator.top or accelerator.name, accelerator, _ROLE)


class SoftwareAccelerator:
    """One ROS-SW accelerator block: its input slots and its function.

    Args:
        block: The accelerator block.
        accelerator: Its type.
        function: What it runs (see `load_function`).
    """

    def __init__(self, block: Block, accelerator: AcceleratorType, function: Function) -> None:
        self.name = block.name
        self.inputs = tuple(port.name for port in block.inputs)
        self.outputs = tuple(port.name for port in block.outputs)
        self.output_types = tuple(port.message for port in block.outputs)
        self.function = function
        self._slots: list[Any] = [None] * len(self.inputs)
        self.calls = 0

    def take(self, port: int, message: object) -> bool:
        """Put a message on an input; return whether it replaced one not yet used."""
        replaced = self._slots[port] is not None
        self._slots[port] = message
        return replaced

    def ready(self) -> bool:
        """Whether every input holds a message."""
        return all(slot is not None for slot in self._slots)

    def waiting(self) -> int:
        """Messages held on inputs, waiting for the others."""
        return sum(slot is not None for slot in self._slots)

    def fire(self) -> list[object | None]:
        """Run the function on the held messages; one entry per output port.

        Raises:
            RfcError: The function raised, or returned something that does not fit its outputs.
        """
        arguments, self._slots = self._slots, [None] * len(self.inputs)
        self.calls += 1
        try:
            result = self.function(*arguments)
        except RfcError:  # a C-simulated HLS accelerator says what went wrong itself
            raise
        except Exception as exc:  # the user's function failed: stop with its words
            raise RfcError(
                f"ROS-SW accelerator '{self.name}' raised {type(exc).__name__}: {exc} "
                f"(call {self.calls})"
            ) from None
        return self._check(self._per_port(result))

    def _per_port(self, result: Any) -> Sequence[Any]:
        if isinstance(result, dict):
            unknown = sorted(set(result) - set(self.outputs))
            if unknown:
                raise RfcError(
                    f"ROS-SW accelerator '{self.name}' returned output '{unknown[0]}', but its "
                    f"outputs are {', '.join(self.outputs)}"
                )
            return [result.get(name) for name in self.outputs]
        if len(self.outputs) == 1:
            return [result]
        if not isinstance(result, tuple | list) or len(result) != len(self.outputs):
            raise RfcError(
                f"ROS-SW accelerator '{self.name}' has {len(self.outputs)} outputs and must "
                f"return a tuple of {len(self.outputs)} messages (None for no message), not "
                f"{type(result).__name__}"
            )
        return list(result)

    def _check(self, messages: Sequence[Any]) -> list[object | None]:
        for name, expected, message in zip(self.outputs, self.output_types, messages, strict=True):
            if message is None:
                continue
            got = getattr(message, "__msgtype__", type(message).__name__)
            if got != expected:
                raise RfcError(
                    f"ROS-SW accelerator '{self.name}' returned a {got} on output '{name}', "
                    f"which carries {expected}"
                )
        return list(messages)
