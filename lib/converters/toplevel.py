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
import types
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from myhdl import ResetSignal, Signal, block, intbv

from rfc.lib.converters.ports import WIRES, Port, PortRole
from rfc.toolchain import start_new_design

_serial = itertools.count()


def port_signals(ports: Sequence[Port]) -> dict[str, Any]:
    """Create one signal per port: bool for wires and bools, else intbv; sync active-high reset."""
    signals: dict[str, Any] = {}
    for port in ports:
        if port.role is PortRole.RESET:
            signals[port.name] = ResetSignal(0, active=1, isasync=False)
        elif port.role in WIRES or port.ros_type == "bool":
            signals[port.name] = Signal(bool(0))
        else:
            signals[port.name] = Signal(intbv(0)[port.bits :])
    return signals


def top_block(
    name: str, port_names: Sequence[str], body: Callable[..., Any], **parameters: Any
) -> Any:
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
        name=name, args=arguments, body=[ast.Return(call)], decorator_list=[], type_params=[]
    )
    module = ast.fix_missing_locations(ast.Module(body=[function], type_ignores=[]))
    source = ast.unparse(module) + "\n"
    # MyHDL reads the function's source through `inspect`, which looks in linecache, and maps
    # every frame to its module: registering one keeps that lookup from rescanning sys.modules.
    module = types.ModuleType(f"rfc_generated_top_{next(_serial)}")
    module.__file__ = f"<{module.__name__}>"
    linecache.cache[module.__file__] = (
        len(source),
        None,
        source.splitlines(keepends=True),
        module.__file__,
    )
    sys.modules[module.__name__] = module
    module.__dict__.update(_body=body, _parameters=parameters)
    exec(compile(source, module.__file__, "exec"), module.__dict__)  # source built from an AST
    return block(module.__dict__[name])


@contextlib.contextmanager
def elaboration() -> Iterator[None]:
    """Elaborate and convert MyHDL designs quickly, with names that do not depend on history.

    Two things in MyHDL (0.11.52) need help when one process generates many designs:

    * it calls `inspect.stack()` for every block and process it creates, to learn its caller;
      the standard one reads the source context of every frame on the stack, which dominates
      the time to elaborate a converter with hundreds of field registers. Within this context
      `inspect.stack` returns the same frames without source context;
    * it makes block names unique against every name used since the process started, growing
      them with each design (``x_0_1_2 ...``) until VHDL refuses them; the context starts from
      an empty set of names.

    The context is not thread-safe.
    """
    original = inspect.stack

    def stack(context: int = 1) -> list[inspect.FrameInfo]:
        frame = sys._getframe(1)
        records = []
        while frame is not None:
            code = frame.f_code
            records.append(
                inspect.FrameInfo(frame, code.co_filename, frame.f_lineno, code.co_name, None, None)
            )
            frame = frame.f_back
        return records

    start_new_design()
    inspect.stack = stack
    try:
        yield
    finally:
        inspect.stack = original
