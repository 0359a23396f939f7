"""ROS-SW accelerators: a Python function run on rosbags message objects (the software fallback).

Calling convention (docs/runtime.md): the function takes one rosbags message object per input
port, positionally in the order the accelerator declares its inputs, and returns, for one output
port, a message object or None (no message this time); for several, a tuple with one entry per
output port in declaration order (None where it sends nothing), or a dict of port name to
message.

Which function is decided at build time (`rfc.lower.runtime_plan`); the plan names it.

An accelerator with several inputs fires when every input has received a message since it last
fired, on the newest message of each; a message replaced by a newer one before that is counted
as superseded.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from rfc.errors import RfcError
from rfc.user_code import running_user_code

Function = Callable[..., Any]


@dataclass(frozen=True)
class SoftwareBlock:
    """A ROS-SW accelerator block as the plan names it: its ports and its function's place.

    Attributes:
        name: The block's name.
        module: The file of its function, relative to the plan.
        function: The function's name in that file.
        inputs: Its input ports' names, in declaration order.
        outputs: Its output ports' names, in declaration order.
        output_types: The message type of each output port.
    """

    name: str
    module: str
    function: str
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    output_types: tuple[str, ...]


class SoftwareAccelerator:
    """One ROS-SW accelerator block at run time: its input slots and its loaded function.

    Args:
        block: The block as the plan names it.
        function: What it runs (``block.function`` imported).
    """

    def __init__(self, block: SoftwareBlock, function: Function) -> None:
        self.block = block
        self.function = function
        self._slots: list[Any] = [None] * len(block.inputs)
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
        arguments, self._slots = self._slots, [None] * len(self.block.inputs)
        self.calls += 1
        what = (
            f"ROS-SW function '{getattr(self.function, '__name__', '?')}' of accelerator "
            f"'{self.block.name}' (call {self.calls})"
        )
        try:
            with running_user_code(what):
                result = self.function(*arguments)
        except RfcError:  # a time limit, or a C-simulated HLS accelerator's own sentence
            raise
        except Exception as exc:  # the user's function failed: stop with its words
            raise RfcError(
                f"ROS-SW accelerator '{self.block.name}' raised {type(exc).__name__}: {exc} "
                f"(call {self.calls})"
            ) from None
        return self._check(self._per_port(result))

    def _per_port(self, result: Any) -> Sequence[Any]:
        name, outputs = self.block.name, self.block.outputs
        if isinstance(result, dict):
            unknown = sorted(set(result) - set(outputs))
            if unknown:
                raise RfcError(
                    f"ROS-SW accelerator '{name}' returned output '{unknown[0]}', but its "
                    f"outputs are {', '.join(outputs)}"
                )
            return [result.get(output) for output in outputs]
        if len(outputs) == 1:
            return [result]
        if not isinstance(result, tuple | list) or len(result) != len(outputs):
            raise RfcError(
                f"ROS-SW accelerator '{name}' has {len(outputs)} outputs and must "
                f"return a tuple of {len(outputs)} messages (None for no message), not "
                f"{type(result).__name__}"
            )
        return list(result)

    def _check(self, messages: Sequence[Any]) -> list[object | None]:
        block = self.block
        for name, expected, message in zip(
            block.outputs, block.output_types, messages, strict=True
        ):
            if message is None:
                continue
            got = getattr(message, "__msgtype__", type(message).__name__)
            if got != expected:
                raise RfcError(
                    f"ROS-SW accelerator '{block.name}' returned a {got} on output '{name}', "
                    f"which carries {expected}"
                )
        return list(messages)
