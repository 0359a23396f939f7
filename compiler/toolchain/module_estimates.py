"""Each module of a logic mapped once, cached by content; the whole logic timed from them.

`module_estimate` maps one module of rfc's own Verilog out of context (`rfc.toolchain.yosys`:
`synth_xilinx -abc9`, cells counted, `sta`, its boundary logic kept: the mapped cells between
its ports and its first registers), all cached by the content of its file, its module's name
left out (a system's estimate sums its modules, so a rebuild or a sibling system that shares
blocks maps only what changed; two builds that miss one module at once map it once);
`estimate_modules` runs several at once, the largest first, and `logic_timing` times a whole
logic from them: each block's own path, and the paths that cross blocks from the modules'
boundary logic (`crossing_timing`), without mapping or reading their insides again.
"""

from __future__ import annotations

import dataclasses
import fcntl
import hashlib
import json
import os
import re
import tempfile
import threading
from collections.abc import Iterator, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from rfc.toolchain.cache import cache_root
from rfc.toolchain.convert import canonical_lines
from rfc.toolchain.sta import TimingPath
from rfc.toolchain.yosys import Module, Resources, flattened_timing, map_module, yosys_version

#: Changes whenever the way a module is mapped or timed changes, so old cache entries go unused.
_FLOW = (
    "synth_xilinx -family xc7 -noiopad -abc9 -flatten, no cells_xtra, no brams map, sta, "
    "boundary logic, v5"
)
#: The same for a module that instantiates others (`module_estimate`'s `submodules`).
_SUBMODULE_FLOW = "submodules as black boxes, out of sta, their ports' cones in the boundary, v2"
#: How many modules are mapped at once (the development machines have two cores).
WORKERS = 2


@dataclass(frozen=True)
class ModuleEstimate:
    """One module mapped to the 7-series out of context.

    Attributes:
        resources: Its cells.
        timing: Its critical path, None when nothing in it is timed (a module of wires).
        netlist: Its boundary logic, mapped (Verilog of 7-series cells): the cells on the paths
            from its inputs to its first registers and from its last registers to its outputs,
            for timing the paths that cross from one block into another.
    """

    resources: Resources
    timing: TimingPath | None
    netlist: Path


def cache_directory() -> Path:
    """Where module figures are kept: ``$RFC_CACHE_DIR/verilog`` or ``~/.cache/rfc/verilog``."""
    return cache_root() / "verilog"


def module_estimate(verilog: Path, top: str, submodules: Sequence[Path] = ()) -> ModuleEstimate:
    """Map one Verilog file to the 7-series with `-abc9`; count and time its module `top`.

    The modules `top` instantiates are in `submodules`, one per file named after it: they are
    mapped on their own, so here they are black boxes, their cells not counted and their ports
    taken as registered (`logic_timing` joins the paths across them).

    The figures and the boundary logic are cached by the file's content with the module's
    name left out, the submodules' files, and Yosys's version: the same block under another
    name (a slice, a busy watch or a manager of a sibling system, named after its project) is
    mapped once.

    Raises:
        RuntimeError: Yosys is missing or fails.
    """
    digest = hashlib.sha256()
    for part in (_FLOW, yosys_version(), *canonical_lines(_renamed(verilog.read_text(), top))):
        digest.update(part.encode() + b"\n")
    if submodules:
        digest.update(_SUBMODULE_FLOW.encode() + b"\n")
    for submodule in submodules:
        digest.update(submodule.read_bytes())
    entry = cache_directory() / f"{digest.hexdigest()}.json"
    anonymous = entry.with_suffix(".v")  # the boundary logic, its module named _ANONYMOUS
    if not (entry.is_file() and anonymous.is_file()):
        entry.parent.mkdir(parents=True, exist_ok=True)
        with _claimed(entry):
            if not (entry.is_file() and anonymous.is_file()):  # nobody mapped it meanwhile
                _map_module(Module(verilog, top, tuple(submodules)), entry, anonymous)
    return _read_entry(entry, _named(anonymous, top))


#: The name a cached module goes by, whatever the name it was mapped under.
_ANONYMOUS = "rfc_estimated_module"


def _renamed(text: str, name: str, to: str = _ANONYMOUS) -> str:
    """Verilog `text` with every occurrence of the identifier `name` made `to`."""
    return re.sub(rf"(?<![\w$]){re.escape(name)}(?![\w$])", to, text)


def _named(anonymous: Path, top: str) -> Path:
    """The cached boundary logic `anonymous` as module `top` (written once, beside it)."""
    named = anonymous.with_name(f"{anonymous.stem}.{top}.v")
    if not named.is_file():
        _publish(named, _renamed(anonymous.read_text(), _ANONYMOUS, top))
    return named


@contextmanager
def _claimed(entry: Path) -> Iterator[None]:
    """Hold `entry`'s lock: of two processes (or threads) needing one module, one maps it.

    Parallel builds and test workers sharing a cache would otherwise both map a module they
    both miss (minutes for an accelerator); the second waits and reads the first's figures.
    """
    with entry.with_suffix(".lock").open("a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)


def _map_module(module: Module, entry: Path, anonymous: Path) -> None:
    """Map, count and time `module`; publish its figures and boundary logic.

    The figures go to `entry`, the boundary logic to `anonymous` with the module renamed
    `_ANONYMOUS` (`_named` gives it back under any name).
    """
    with tempfile.TemporaryDirectory(prefix="rfc-synth-") as scratch:
        resources, timing, boundary = map_module(module, Path(scratch))
        _publish(anonymous, _renamed(boundary.read_text(), module.top))
    value = {
        "resources": dataclasses.asdict(resources),
        "timing": None if timing is None else dataclasses.asdict(timing),
    }
    _publish(entry, json.dumps(value))


def estimate_modules(
    modules: Sequence[tuple[Path, str]], submodules: Mapping[str, Sequence[Path]] | None = None
) -> list[ModuleEstimate]:
    """`module_estimate` of each (file, module), `WORKERS` Yosys processes at a time.

    `submodules` gives, by module name, the files of the modules it instantiates (none when
    missing). The largest files start first: an accelerator's mapping takes minutes where the
    converters take seconds, so the others fill the second worker around it instead of
    delaying its start.
    """
    children = submodules or {}
    with ThreadPoolExecutor(max_workers=WORKERS) as pool:
        started = {
            module: pool.submit(module_estimate, *module, children.get(module[1], ()))
            for module in sorted(modules, key=lambda m: m[0].stat().st_size, reverse=True)
        }
        return [started[module].result() for module in modules]


def crossing_timing(netlists: Sequence[Path], top_verilog: Path, top: str) -> TimingPath | None:
    """The critical path among the paths that leave or enter a block of a whole logic.

    `netlists` are the modules' boundary logic (`ModuleEstimate.netlist`): every path that
    crosses from one block into another runs through them from register to register, so `sta`
    of the top level over them, flattened, finds the latest such path as it would over the
    whole netlists, at a fraction of their size. Paths inside one block are the modules' own.
    The result is cached by the content of every file.

    Raises:
        RuntimeError: Yosys is missing or fails.
    """
    digest = hashlib.sha256()
    for part in (_FLOW, yosys_version(), top, *canonical_lines(top_verilog.read_text())):
        digest.update(part.encode() + b"\n")
    for netlist in netlists:
        digest.update(netlist.read_bytes())
    entry = cache_directory() / f"{digest.hexdigest()}.system.json"
    if entry.is_file():
        value = json.loads(entry.read_text())
        return None if value is None else TimingPath(**value)
    timing = flattened_timing([*netlists, top_verilog], top)
    entry.parent.mkdir(parents=True, exist_ok=True)
    _publish(entry, json.dumps(None if timing is None else dataclasses.asdict(timing)))
    return timing


def logic_timing(
    instances: Mapping[str, ModuleEstimate], top_verilog: Path, top: str
) -> TimingPath | None:
    """The critical path of a whole logic, from its blocks' estimates (by instance label).

    A path of the flattened logic either stays inside one block, where it is that module's own
    (its ports taken as registered: a path from an input there is never longer than the real
    one through that input, which crosses), or crosses into or out of a block, where
    `crossing_timing` finds it. The latest of them is the one `sta` of the whole flattened
    netlist finds; a path inside a block is named by its instance (``label.register``).

    Raises:
        RuntimeError: Yosys is missing or fails.
    """
    netlists = list(dict.fromkeys(module.netlist for module in instances.values()))
    paths = [crossing_timing(netlists, top_verilog, top)]
    paths += [_inside(label, module.timing) for label, module in instances.items()]
    return max((p for p in paths if p is not None), key=lambda p: p.delay_ps, default=None)


def _inside(label: str, path: TimingPath | None) -> TimingPath | None:
    """A module's own path, named as it lies in the whole logic (under its instance label)."""
    if path is None:
        return None
    return dataclasses.replace(path, start=f"{label}.{path.start}", end=f"{label}.{path.end}")


def _read_entry(entry: Path, netlist: Path) -> ModuleEstimate:
    value = json.loads(entry.read_text())
    timing = value["timing"]
    return ModuleEstimate(
        Resources(**value["resources"]),
        None if timing is None else TimingPath(**timing),
        netlist,
    )


def _publish(path: Path, text: str) -> None:
    """Write a cache file whole or not at all (another process may be reading the cache)."""
    partial = path.with_suffix(f"{path.suffix}.{os.getpid()}.{threading.get_ident()}.tmp")
    partial.write_text(text)
    partial.replace(path)
