"""Top-level MyHDL blocks whose ports carry exactly the names of a generated port list.

MyHDL names the ports of a converted design after the parameters of the top-level function,
which it reads from the function's source. A converter's ports depend on the message, so the
top-level function is built here with Python's `ast` module — a signature listing the port
names and a body that forwards them, as keywords, to the real (generic) block. The other ways
MyHDL offers (`HdlClass`, interface objects) lose the declarations of their `_num` signals when
converting with ``std_logic_ports`` (myhdl 0.11.52), so they cannot be used.
"""

from __future__ import annotations

import ast
import contextlib
import inspect
import itertools
import linecache
import sys
import threading
import types
from collections.abc import Callable, Hashable, Iterable, Iterator, MutableSet, Sequence
from dataclasses import dataclass, field
from typing import Any

from myhdl import ResetSignal, Signal, block, intbv
from myhdl import _block as myhdl_block_module
from myhdl import _instance as myhdl_instance_module
from myhdl import _visitors as myhdl_visitors_module
from myhdl.conversion import _analyze as myhdl_analyze_module

from rfc.lib.converters.ports import WIRES, Port, PortRole
from rfc.lib.types import Instances, SignalLike
from rfc.toolchain import start_new_design

_serial = itertools.count()


def port_signals(ports: Sequence[Port]) -> dict[str, SignalLike]:
    """Create one signal per port: bool for wires and bools, else intbv; sync active-high reset."""
    signals: dict[str, SignalLike] = {}
    for port in ports:
        if port.role is PortRole.RESET:
            signals[port.name] = ResetSignal(0, active=1, isasync=False)
        elif port.role in WIRES or port.ros_type == "bool":
            signals[port.name] = Signal(bool(0))
        else:
            signals[port.name] = Signal(intbv(0)[port.bits :])
    return signals


def top_block(
    name: str, port_names: Sequence[str], body: Callable[..., Instances], **parameters: object
) -> Callable[..., Instances]:
    """Return a ``@block`` function `name` whose parameters are `port_names`.

    Calling it with the port signals (as keywords) elaborates the block
    ``body(**parameters, **signals)``; converting the result gives an entity with exactly these
    port names, in this order.
    """
    arguments = ast.arguments(
        posonlyargs=[],
        args=[ast.arg(arg=port) for port in port_names],
        kwonlyargs=[],
        kw_defaults=[],
        defaults=[],
    )
    call = ast.Call(
        func=ast.Name("_body", ast.Load()),
        args=[],
        keywords=[
            ast.keyword(value=ast.Name("_parameters", ast.Load())),
            *(ast.keyword(arg=port, value=ast.Name(port, ast.Load())) for port in port_names),
        ],
    )
    function = ast.FunctionDef(
        name=name, args=arguments, body=[ast.Return(call)], decorator_list=[]
    )
    module = ast.fix_missing_locations(ast.Module(body=[function], type_ignores=[]))
    source = ast.unparse(module) + "\n"
    # MyHDL reads the function's source through `inspect`, which finds it in linecache.
    module_name = f"rfc_generated_top_{next(_serial)}"
    filename = f"<{module_name}>"
    linecache.cache[filename] = (len(source), None, source.splitlines(keepends=True), filename)
    namespace: dict[str, Any] = {"_body": body, "_parameters": parameters, "__name__": module_name}
    exec(compile(source, filename, "exec"), namespace)  # source built from an AST
    return block(namespace[name])


def _frames_without_context(context: int = 1) -> list[inspect.FrameInfo]:
    """`inspect.stack` without reading source lines: the caller's frames, outermost last."""
    frame: types.FrameType | None = sys._getframe(1)
    records = []
    while frame is not None:
        code = frame.f_code
        records.append(
            inspect.FrameInfo(frame, code.co_filename, frame.f_lineno, code.co_name, None, None)
        )
        frame = frame.f_back
    return records


class _QuickInspect(types.ModuleType):
    """The `inspect` module as MyHDL's own modules see it inside `elaboration`: a quick `stack`."""

    stack = staticmethod(_frames_without_context)

    def __getattr__(self, name: str) -> Any:
        return getattr(inspect, name)


class _InsertionOrderedSet(MutableSet[Hashable]):
    """A set that iterates in insertion order, for MyHDL's sets of signal names.

    MyHDL collects the signals a process reads and writes in plain sets of names and writes
    sensitivity lists and reset branches in their iteration order, which follows the string
    hashes and so changes from process to process. In insertion order (the order of the source)
    the same design converts to the same bytes every time.
    """

    def __init__(self, items: Iterable[Hashable] = ()) -> None:
        self._items = dict.fromkeys(items)

    def __contains__(self, item: object) -> bool:
        return item in self._items

    def __iter__(self) -> Iterator[Hashable]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def add(self, value: Hashable) -> None:
        self._items[value] = None

    def discard(self, value: Hashable) -> None:
        self._items.pop(value, None)

    def __repr__(self) -> str:
        return f"{{{', '.join(map(repr, self._items))}}}"


_ABSENT = object()
#: The MyHDL modules that call `inspect.stack()` for every block and process they create.
_STACK_CALLERS = (myhdl_block_module, myhdl_instance_module)
#: The MyHDL modules that gather signal names in sets that decide the order of the output.
_NAME_SET_USERS = (myhdl_visitors_module, myhdl_analyze_module)


@contextlib.contextmanager
def elaboration() -> Iterator[None]:
    """Elaborate and convert MyHDL designs quickly, with names that do not depend on history.

    Three things in MyHDL (0.11.52) need help when one process generates many designs:

    * it calls `inspect.stack()` for every block and process it creates, to learn its caller;
      the standard one reads the source context of every frame on the stack, which dominates
      the time to elaborate a converter with hundreds of field registers. Within this context
      the two MyHDL modules that call it see an `inspect` whose `stack` returns the same frames
      without source context; the `inspect` module itself, and everyone else's use of it, is
      never changed;
    * it makes block names unique against every name used since the process started, growing
      them with each design (``x_0_1_2 ...``) until VHDL refuses them; the context starts from
      an empty set of names;
    * it orders sensitivity lists and reset branches by string hashes, so the same design gave
      different bytes in every process (and missed every cache keyed by content): within the
      context, the two MyHDL modules that collect those names use insertion-ordered sets.

    Elaborate and convert inside the same context. Contexts nest, and one thread at a time holds
    one (MyHDL's own elaboration is not thread-safe); the outermost restores every module it
    touched on exit.
    """
    with _ELABORATING:
        if _patched.depth == 0:
            _patch_myhdl()
        _patched.depth += 1
        start_new_design()
        try:
            yield
        finally:
            _patched.depth -= 1
            if _patched.depth == 0:
                _restore_myhdl()


@dataclass
class _Patched:
    """The open `elaboration` contexts of the thread holding the lock; what the first replaced."""

    depth: int = 0
    saved: list[tuple[types.ModuleType, str, object]] = field(default_factory=list)


_patched = _Patched()
#: One thread elaborates at a time: MyHDL's naming state is global, and the patch is undone only
#: when the outermost context closes.
_ELABORATING = threading.RLock()


def _patch_myhdl() -> None:
    replacements: list[tuple[types.ModuleType, str, object]]
    replacements = [(module, "inspect", _QuickInspect("inspect")) for module in _STACK_CALLERS]
    replacements += [(module, "set", _InsertionOrderedSet) for module in _NAME_SET_USERS]
    _patched.saved = [
        (module, name, vars(module).get(name, _ABSENT)) for module, name, _ in replacements
    ]
    for module, name, value in replacements:
        setattr(module, name, value)


def _restore_myhdl() -> None:
    for module, name, value in _patched.saved:
        if value is _ABSENT:
            delattr(module, name)
        else:
            setattr(module, name, value)
