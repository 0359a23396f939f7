"""Accelerator types in Python: `accelerator` on MyHDL blocks, `external_accelerator` else."""

from __future__ import annotations

import inspect
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rfc.errors import RfcError, SourceLocation
from rfc.ir.model import (
    AcceleratorKind,
    AcceleratorType,
    Direction,
    FieldSelection,
    FunctionRef,
    Port,
)
from rfc.spec import common
from rfc.spec.python_calls import as_text, as_texts, call_site


@dataclass(frozen=True)
class PortSpec:
    """A port's message type and, for inputs, the fields the accelerator needs."""

    message: str
    needs: FieldSelection = field(default_factory=FieldSelection)


def port(message: str, *, include: Iterable[str] = (), exclude: Iterable[str] = ()) -> PortSpec:
    """Describe an accelerator port that needs only some fields of its message.

    Args:
        message: The message type.
        include: The only fields the accelerator reads (dotted paths, ``*`` wildcards).
        exclude: Fields it does not read.
    """
    location, _ = call_site()
    return PortSpec(
        as_text(message, "port message", location),
        FieldSelection(
            as_texts(include, "include", location), as_texts(exclude, "exclude", location)
        ),
    )


def _ports(spec: Any, direction: Direction, location: SourceLocation) -> tuple[Port, ...]:
    what = "inputs" if direction is Direction.IN else "outputs"
    if isinstance(spec, str | PortSpec):
        spec = [spec]
    if isinstance(spec, Mapping):
        named = list(spec.items())
    elif isinstance(spec, Iterable):
        named = [(common.default_port_name(direction.value, i), s) for i, s in enumerate(spec)]
    else:
        raise RfcError(
            f"{what} must be a message type, a list of them, or a dict of port name to "
            f"message type, not {spec!r}",
            location=location,
        )
    ports = []
    for name, item in named:
        port_spec = (
            item
            if isinstance(item, PortSpec)
            else PortSpec(as_text(item, f"the message of port '{name}'", location))
        )
        ports.append(
            Port(
                name=as_text(name, f"a port name of {what}", location),
                direction=direction,
                message=port_spec.message,
                location=location,
                needs=port_spec.needs,
            )
        )
    return tuple(ports)


def _function_ref(function: Any, what: str, location: SourceLocation) -> FunctionRef:
    if not callable(function) or not hasattr(function, "__name__"):
        raise RfcError(f"{what} must be a Python function, not {function!r}", location=location)
    source = inspect.getsourcefile(function)
    if source is None:
        raise RfcError(f"{what} '{function.__name__}' has no source file", location=location)
    return FunctionRef(Path(source).resolve(), function.__name__)


class AcceleratorDefinition:
    """An accelerator type defined in Python; calling it calls the MyHDL block function."""

    def __init__(self, definition: AcceleratorType) -> None:
        self.definition = definition
        if definition.block_function is not None:
            self.__name__ = definition.block_function.__name__
            self.__doc__ = definition.block_function.__doc__
            self.__wrapped__ = definition.block_function

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        """Instantiate the MyHDL block (for simulation and conversion)."""
        if self.definition.block_function is None:
            raise RfcError(
                f"{self.definition.kind.value} accelerator '{self.definition.name}' has no "
                "Python block to call",
                location=call_site()[0],
            )
        return self.definition.block_function(*args, **kwargs)

    def __repr__(self) -> str:
        return f"<rfc accelerator {self.definition.name} ({self.definition.kind.value})>"


def accelerator(
    *,
    inputs: Any,
    outputs: Any,
    reference: Callable[..., Any] | None = None,
    name: str | None = None,
) -> Callable[[Any], AcceleratorDefinition]:
    """Annotate a MyHDL ``@block`` function with its ROS message ports.

    Args:
        inputs: The input ports: a message type, a list of them (ports ``in0``, ``in1``...),
            or a dict of port name to message type or `port(...)`.
        outputs: The output ports, likewise (``out0``, ...).
        reference: The Python reference model of the accelerator.
        name: The type name (default: the function's name).

    Returns:
        A decorator; put it above ``@block``.
    """
    location, _ = call_site()
    input_ports = _ports(inputs, Direction.IN, location)
    output_ports = _ports(outputs, Direction.OUT, location)
    reference_ref = None if reference is None else _function_ref(reference, "reference", location)

    def decorate(block_function: Any) -> AcceleratorDefinition:
        function = getattr(block_function, "func", None)
        if not type(block_function).__module__.startswith("myhdl") or not callable(function):
            called = getattr(block_function, "__name__", None)
            got = type(block_function).__name__ + (f" '{called}'" if called else "")
            raise RfcError(
                f"@rfc.accelerator expects a MyHDL @block function, but got {got}",
                location=location,
                hint="put @block (from myhdl) between @rfc.accelerator and the function",
            )
        source = _function_ref(function, "the block function", location)
        return AcceleratorDefinition(
            AcceleratorType(
                name=as_text(name or function.__name__, "name", location),
                kind=AcceleratorKind.MYHDL,
                sources=(source.file,),
                inputs=input_ports,
                outputs=output_ports,
                location=location,
                top=function.__name__,
                reference=reference_ref,
                block_function=block_function,
                reference_function=reference,
            )
        )

    return decorate


def external_accelerator(
    name: str,
    *,
    kind: str,
    sources: str | Iterable[str],
    inputs: Any,
    outputs: Any,
    top: str | None = None,
    reference: Callable[..., Any] | None = None,
) -> AcceleratorDefinition:
    """Define an accelerator written outside Python: HLS C++, VHDL, or ROS-SW.

    Args:
        name: The type name.
        kind: ``HLS``, ``VHDL``, ``MyHDL`` or ``ROS-SW``.
        sources: Source files, relative to the calling file.
        inputs: Input ports, as for `accelerator`.
        outputs: Output ports, as for `accelerator`.
        top: Top-level function or entity, when it matters.
        reference: The Python reference model.
    """
    location, base = call_site()
    chosen = common.accelerator_kind(as_text(kind, "kind", location), location)
    owner = f"accelerator '{name}'"
    files = [
        (common.source_file(text, base, "source file", location), location)
        for text in as_texts(sources, "sources", location)
    ]
    if not files:
        raise RfcError(f"{owner} lists no source files", location=location)
    common.check_source_suffixes(chosen, files, owner)
    return AcceleratorDefinition(
        AcceleratorType(
            name=as_text(name, "name", location),
            kind=chosen,
            sources=tuple(path for path, _ in files),
            inputs=_ports(inputs, Direction.IN, location),
            outputs=_ports(outputs, Direction.OUT, location),
            location=location,
            top=top,
            reference=None
            if reference is None
            else _function_ref(reference, "reference", location),
            reference_function=reference,
        )
    )
