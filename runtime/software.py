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
from typing import Any

from rfc.errors import RfcError
from rfc.user_code import running_user_code

Function = Callable[..., Any]


class SoftwareAccelerator:
    """One ROS-SW accelerator block: its input slots and its function.

    Args:
        name: The block's name.
        inputs: Its input ports' names, in declaration order.
        outputs: Its output ports' names, in declaration order.
        output_types: The message type of each output port.
        function: What it runs.
    """

    def __init__(
        self,
        name: str,
        inputs: tuple[str, ...],
        outputs: tuple[str, ...],
        output_types: tuple[str, ...],
        function: Function,
    ) -> None:
        self.name = name
        self.inputs = inputs
        self.outputs = outputs
        self.output_types = output_types
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
        what = (
            f"ROS-SW function '{getattr(self.function, '__name__', '?')}' of accelerator "
            f"'{self.name}' (call {self.calls})"
        )
        try:
            with running_user_code(what):
                result = self.function(*arguments)
        except RfcError:  # a time limit, or a C-simulated HLS accelerator's own sentence
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
