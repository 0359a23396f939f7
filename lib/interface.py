"""Interface objects: a message on an accelerator port as MyHDL signals named like its fields.

A MyHDL accelerator written against typed interfaces receives, per message port, one
`MessageInterface` whose attributes mirror the message by its ROS field names
(``info.roi.x_offset``); a fixed-size array is a list (``tri.vertex_indices[2]``), a string or
primitive sequence a stream object (``length``, ``data``, ``keep``, ``valid``, ``ready``,
``last``), a sequence of messages an object with ``length``, ``valid``, ``ready``, ``last`` and
the element's fields; the message's own handshake is ``valid``/``ready``. Where each signal
sits comes from the message signature (`rfc.lib.converters.ports.Port.member`).

MyHDL cannot put a list of signals on a top-level port, so the generated top level keeps flat
ports and `typed_block` hands the objects in: it builds them from the flat port signals and
copies the elements of each list of signals to or from their ports. MyHDL does not follow an
attribute of a list element inside a generator (``info.points[1].x``): bind such a signal to a
name at elaboration (``x1 = info.points[1].x``) and use the name in the generator.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

from myhdl import Signal, block

from rfc.lib.converters.ports import Direction, Port
from rfc.lib.converters.wiring import follow
from rfc.lib.types import Instances, Member, SignalLike

#: A member step: an attribute name or a fixed-array index.
Step = str | int


class MessageInterface:
    """The signals of a message, a sub-message or a stream, as attributes named after fields.

    Args:
        what: What it is, for its `repr` (``port info: sensor_msgs/CameraInfo``).
    """

    def __init__(self, what: str) -> None:
        self._what = what

    def __repr__(self) -> str:
        members = ", ".join(name for name in vars(self) if not name.startswith("_"))
        return f"<{self._what}: {members}>"


@dataclass(frozen=True)
class ArrayPins:
    """A list of signals of an interface object and the flat pins its elements copy.

    Attributes:
        elements: The list the accelerator indexes.
        pins: The flat port signal of each element (None for an element not selected).
        inward: Per element, whether it is an input of the accelerator.
    """

    elements: list[SignalLike]
    pins: list[SignalLike | None]
    inward: list[bool]


def interface_object(
    ports: Sequence[Port], signals: Mapping[str, SignalLike], what: str
) -> tuple[MessageInterface, list[ArrayPins]]:
    """Arrange the signals of one port's signature as an interface object.

    Args:
        ports: The port's signature (accelerator side: `direction` as the accelerator sees it).
        signals: The flat port signals by port name.
        what: Description of the port, for `repr`.

    Returns:
        The object, and its lists of signals with the pins they copy (`array_copies` makes
        the copies; MyHDL wants blocks instantiated by the block that returns them).
    """
    root = MessageInterface(what)
    arrays: dict[int, tuple[list[SignalLike], list[Port]]] = {}
    for port in ports:
        container, last = _container(root, port.member, what)
        signal = signals[port.name]
        if isinstance(last, int):
            container.extend([None] * (last + 1 - len(container)))
            container[last] = signal
            arrays.setdefault(id(container), (container, []))[1].append(port)
        else:
            setattr(container, last, signal)
    copies = []
    for elements, array_ports in arrays.values():
        # One list for MyHDL: the elements the accelerator uses, copied from or to their pins.
        pins: list[SignalLike | None] = [None] * len(elements)
        inward = [False] * len(elements)
        for port in array_ports:
            index = port.member[-1]
            assert isinstance(index, int)
            pin = signals[port.name]
            pins[index] = pin
            elements[index] = Signal(pin.val)
            inward[index] = port.direction is Direction.IN
        copies.append(ArrayPins(elements, pins, inward))
    return root, copies


def _container(root: MessageInterface, member: tuple[Step, ...], what: str) -> tuple[Member, Step]:
    """The object or list that holds the last step of `member`, created on the way."""
    here: Member = root
    for step, following in itertools.pairwise(member):
        fresh: Member = [] if isinstance(following, int) else MessageInterface(f"{what} .{step}")
        if isinstance(step, int):
            here.extend([None] * (step + 1 - len(here)))
            here[step] = here[step] if here[step] is not None else fresh
            here = here[step]
        else:
            if not hasattr(here, step):
                setattr(here, step, fresh)
            here = getattr(here, step)
    return here, member[-1]


@block
def array_copies(array: ArrayPins) -> Instances:
    """Drive each list element from its input pin, or each output pin from its element."""
    return [
        follow(pin, element) if into else follow(element, pin)
        for element, pin, into in zip(array.elements, array.pins, array.inward, strict=True)
        if pin is not None
    ]


def typed_block(
    block_function: Callable[..., Instances], ports: Mapping[str, Sequence[Port]], name: str
) -> Callable[..., Instances]:
    """A MyHDL block with flat ports that calls `block_function` with interface objects.

    Args:
        block_function: The accelerator, ``f(clk, rst, <port>, ...)`` taking interface objects.
        ports: Each message port's signature (flat names, members, accelerator directions).
        name: The block's name (instance names in the converted HDL start with it).

    Returns:
        A ``@block`` function taking ``clk``, ``rst`` and every flat port as keywords.
    """

    def wrapper(**signals: SignalLike) -> Instances:
        objects: dict[str, MessageInterface] = {}
        arrays: list[ArrayPins] = []
        for port, signature in ports.items():
            objects[port], more = interface_object(signature, signals, f"port {port}")
            arrays += more
        copies = [array_copies(array) for array in arrays]
        accelerator = block_function(clk=signals["clk"], rst=signals["rst"], **objects)
        return accelerator, copies

    wrapper.__name__ = wrapper.__qualname__ = name
    return block(wrapper)
