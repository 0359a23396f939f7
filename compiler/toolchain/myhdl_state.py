"""What MyHDL keeps for the whole process, and the contexts that keep one design from another.

MyHDL (0.11.52) holds its naming state, its list of signals and its call counts in module
globals, and reads the source context of every caller while elaborating. rfc elaborates many
designs in one process (a build, a sweep, a test worker): these contexts make each design's
names and bytes independent of what came before, and elaboration quick, without changing
anything another MyHDL user in the process can observe outside them.
"""

from __future__ import annotations

import contextlib
import inspect
import sys
import threading
import types
from collections.abc import Hashable, Iterable, Iterator, MutableSet
from dataclasses import dataclass, field
from typing import Any

from myhdl import _block as myhdl_block
from myhdl import _instance as myhdl_instance
from myhdl import _simulator as myhdl_simulator
from myhdl import _visitors as myhdl_visitors
from myhdl.conversion import _analyze as myhdl_analyze


def start_new_design() -> None:
    """Start MyHDL's instance naming afresh before elaborating a new design.

    MyHDL keeps every instance name it ever gave in module-level sets and makes a repeated name
    unique by appending a suffix per repetition, so a process elaborating many designs (a sweep,
    a test worker) gets names that grow without bound until GHDL rejects them, and that differ
    from run to run. It also numbers each block function's instances (``follow290``) by a count
    of every call in the process, kept until a simulation ends. Names need only be unique within
    one design, and must not depend on what the process built before (the same spec gives the
    same VHDL). Call this before calling the top-level block function.
    """
    myhdl_block._name_set.clear()
    myhdl_block._inst_name_set.clear()
    for decorator in myhdl_simulator._blocks:
        decorator.calls = 0
        for bound in list(decorator.bound_functions.values()):
            bound.calls = 0


@contextlib.contextmanager
def transient_signals() -> Iterator[None]:
    """Have MyHDL forget, on exit, the signals created inside: they must not outlive it.

    MyHDL (0.11.52) keeps every signal the process ever created in one list, never shrinks it,
    and at the end of every simulation resets each signal in it to its initial value (a deep
    copy each). A process that builds and simulates many designs (a test worker, a build
    measuring its converters' latencies, a user's notebook) so keeps every signal alive and
    simulates ever slower: 25 runs of a four-process bench took 0.9 s in a fresh process and
    47 s after 200,000 signals had been created and dropped elsewhere. Wrap work whose signals
    die with it, such as a bench built and run in one go. Contexts nest; only the entries added
    inside are removed, MyHDL's list itself stays in place.
    """
    created = myhdl_simulator._signals
    mark = len(created)
    try:
        yield
    finally:
        del created[mark:]


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
_STACK_CALLERS = (myhdl_block, myhdl_instance)
#: The MyHDL modules that gather signal names in sets that decide the order of the output.
_NAME_SET_USERS = (myhdl_visitors, myhdl_analyze)


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
