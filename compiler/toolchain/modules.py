"""MyHDL's Verilog with chosen blocks as modules of their own, each written once.

MyHDL writes a design as one flat module. Yosys maps a flat module as a whole, so a core
holding three copies of a CORDIC pipeline maps the pipeline three times, and its time grows
with the core's size. `separate_modules` converts each chosen sub-block on its own (a fresh
elaboration of its block function at the same arguments, its signal arguments as ports) into a
module named after its text (``cordic_pipeline_1a2b3c4d``); where two calls or more give the
same module, the parent's conversion writes an instance of it in place of each call's
processes. Only Verilog is affected: the VHDL of a design stays one entity.
"""

from __future__ import annotations

import hashlib
import inspect
import re
from collections import Counter
from collections.abc import Callable, Collection, Hashable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

from myhdl import ResetSignal, Signal
from myhdl import _simulator as myhdl_simulator
from myhdl._extractHierarchy import _UserVerilogCode
from myhdl._Signal import _Signal

#: The name a separated module's text is hashed under, replaced by its real name afterwards.
_PLACEHOLDER = "rfc_separated_module"
_OUTPUT = re.compile(r"^\s*output\s+(?:reg\s+|wire\s+)?(?:signed\s+)?(?:\[[^]]*\]\s*)?(\w+);", re.M)


@dataclass(frozen=True)
class SeparateModule:
    """A block converted as a module of its own.

    Attributes:
        name: The module's name: its block function's name and a hash of its text.
        text: Its Verilog.
        ports: Its port names, in its parameters' order, with whether each is an output.
    """

    name: str
    text: str
    ports: tuple[tuple[str, bool], ...]


#: Elaborates a block (the callable) and converts it to Verilog text under the given name.
ModuleConverter = Callable[[Callable[[], Any], str], str]


def separable(block: Any) -> bool:
    """Whether `block` can become a module: each argument a signal or a value holding none.

    A list of signals (a bus of values) has no port of its own in MyHDL's conversion, nor has
    an interface object (signals as attributes): such a block stays inline. A slice or a
    concatenation of signals is an input like any other.
    """
    return not any(
        _holds_signals(value)
        for value in (*block.args, *block.kwargs.values())
        if not isinstance(value, _Signal)
    )


def _holds_signals(value: Any) -> bool:
    if isinstance(value, (list, tuple)):
        return any(isinstance(v, _Signal) or _holds_signals(v) for v in value)
    members = getattr(value, "__dict__", None)
    return isinstance(members, dict) and any(isinstance(v, _Signal) for v in members.values())


@contextmanager
def separate_modules(
    instance: Any, chosen: Callable[[Any], bool], convert: ModuleConverter
) -> Iterator[list[SeparateModule]]:
    """While inside, the `chosen` sub-blocks of `instance` that repeat convert as instances.

    Calls of one block function at the same parameters (the same plain arguments, signals of
    the same types) become instances of one module, converted once with `convert`; a block
    called once stays inline: its module would be mapped once anyway, and Yosys optimizes it
    better with the logic around it. Yields the distinct modules (write their text beside the
    parent's). The walk does not enter a chosen block, so its own sub-blocks stay in its
    module. On exit every block is as it was.
    """
    calls = [(block, _arguments(block)) for block in _chosen_blocks(instance, chosen)]
    keys = [_call_key(block, arguments) for block, arguments in calls]
    repeated = {key for key, count in Counter(keys).items() if count > 1}
    converted: dict[Hashable, SeparateModule] = {}
    saved: list[tuple[Any, tuple[Any, Any, Any, Any]]] = []
    try:
        for (block, arguments), key in zip(calls, keys, strict=True):
            if key not in repeated:
                continue
            if key not in converted:
                converted[key] = _module_of(block, arguments, convert)
            saved.append((block, (block.verilog_code, block.subs, block.sigdict, block.memdict)))
            _instantiate(block, arguments, converted[key])
        yield list({module.name: module for module in converted.values()}.values())
    finally:
        for block, (code, subs, sigdict, memdict) in saved:
            block.verilog_code, block.subs, block.sigdict, block.memdict = (
                code,
                subs,
                sigdict,
                memdict,
            )


def _chosen_blocks(instance: Any, chosen: Callable[[Any], bool]) -> Iterator[Any]:
    for sub in getattr(instance, "subs", ()):
        if not hasattr(sub, "subs"):  # a process, not a block
            continue
        if sub.verilog_code is None and chosen(sub) and separable(sub):
            yield sub
        else:
            yield from _chosen_blocks(sub, chosen)


def _arguments(block: Any) -> dict[str, Any]:
    """The block's arguments by parameter name."""
    bound = inspect.signature(block.func).bind(*block.args, **block.kwargs)
    bound.apply_defaults()
    return dict(bound.arguments)


def _call_key(block: Any, arguments: dict[str, Any]) -> Hashable:
    """What a call's module depends on: its function, its plain arguments, its signals' types."""
    return (block.func, tuple((name, _shape(value)) for name, value in arguments.items()))


def _shape(value: Any) -> Hashable:
    if not isinstance(value, _Signal):
        return repr(value)
    reset = (value.active, value.isasync) if isinstance(value, ResetSignal) else None
    return (type(value._init).__name__, len(value), value.min, value.max, int(value._init), reset)


def _module_of(block: Any, arguments: dict[str, Any], convert: ModuleConverter) -> SeparateModule:
    """Elaborate `block`'s function afresh at its `arguments` and convert it on its own."""
    fresh = {n: _fresh(v) if isinstance(v, _Signal) else v for n, v in arguments.items()}
    decorated = next(d for d in myhdl_simulator._blocks if d.func is block.func)
    text = convert(lambda: decorated(**fresh), _PLACEHOLDER)
    digest = hashlib.sha256(text.encode()).hexdigest()[:8]
    name = f"{block.func.__name__}_{digest}"
    outputs = set(_OUTPUT.findall(text))
    ports = tuple((n, n in outputs) for n, v in arguments.items() if isinstance(v, _Signal))
    return SeparateModule(name, _renamed(text, name), ports)


def _fresh(signal: Any) -> Any:
    """A signal of `signal`'s type and initial value (a reset keeps its polarity and kind)."""
    if isinstance(signal, ResetSignal):
        return ResetSignal(signal._init, active=signal.active, isasync=signal.isasync)
    return Signal(signal._init)


def _renamed(text: str, name: str) -> str:
    return re.sub(rf"(?<![\w$]){_PLACEHOLDER}(?![\w$])", name, text)


def module_instances(text: str, modules: Collection[str]) -> list[tuple[str, str]]:
    """The (label, module) of each instance of one of `modules` in Verilog `text`.

    Reads the instances `separate_modules` has MyHDL write (``module label (``, a line each).
    """
    return [(label, module) for module, label in _INSTANCE.findall(text) if module in modules]


_INSTANCE = re.compile(r"^(\w+) (\w+) \($", re.M)


def _instantiate(block: Any, arguments: dict[str, Any], module: SeparateModule) -> None:
    """Have MyHDL write an instance of `module` for `block`, its ports marked as used."""
    connections = ",\n".join(f"    .{port}(${port})" for port, _ in module.ports)
    code = f"{module.name} {block.name} (\n{connections}\n);"
    for port, output in module.ports:
        signal = arguments[port]
        if output:
            signal.driven = "wire"
        else:
            signal.read = True
    ports = {port: arguments[port] for port, _ in module.ports}
    block.verilog_code = _UserVerilogCode(code, ports, block.func.__name__, block.func, "", 0)
    # The block's own signals and processes are the module's now: none left to declare.
    block.subs, block.sigdict, block.memdict = [], ports, {}
