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
import itertools
import linecache
from collections.abc import Callable, Sequence
from typing import Any

from myhdl import ResetSignal, Signal, block, intbv

from rfc.lib.converters.ports import WIRES, Port, PortRole
from rfc.lib.types import Instances, SignalLike

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
