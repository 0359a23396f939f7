"""Co-simulation: run a cocotb test module against VHDL in GHDL and report failures plainly."""

from __future__ import annotations

import contextlib
from collections.abc import Mapping, Sequence
from pathlib import Path
from xml.etree import ElementTree

from cocotb_tools.runner import get_runner

from rfc.toolchain.ghdl import STANDARD


class CosimError(AssertionError):
    """A co-simulation test failed or the simulator died; the message holds cocotb's reasons."""


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
) -> int:
    """Build VHDL sources with GHDL and run the cocotb tests of `test_module` on `toplevel`.

    Args:
        sources: VHDL files in compile order.
        toplevel: Entity to simulate.
        test_module: Importable module holding ``@cocotb.test()`` functions.
        build_dir: Scratch folder for this simulation (use a fresh one per configuration).
        env: Extra environment for the test module (how a test learns what to check).
        testcase: Run only this test of the module.
        seed: Random seed for reproducible runs.
        waves: Write a GHW waveform into `build_dir`.

    Returns:
        The number of tests that ran (all passed).

    Raises:
        CosimError: A test failed, or the simulation ended without results.
    """
    build_dir = build_dir.resolve()
    runner = get_runner("ghdl")
    runner.build(
        sources=[Path(s).resolve() for s in sources if Path(s).suffix in (".vhd", ".vhdl")],
        hdl_toplevel=toplevel,
        build_dir=build_dir,
        build_args=[f"--std={STANDARD}", "-fsynopsys"],
        always=True,
        log_file=build_dir / "build.log",
    )
    results = build_dir / "results.xml"
    results.unlink(missing_ok=True)
    # cocotb exits on failure under pytest; the results file says why.
    with contextlib.suppress(SystemExit):
        runner.test(
            test_module=test_module,
            hdl_toplevel=toplevel,
            build_dir=build_dir,
            testcase=testcase,
            seed=seed,
            extra_env=dict(env or {}),
            results_xml=str(results),
            waves=waves,
            test_args=[f"--std={STANDARD}", "-fsynopsys"],
            log_file=build_dir / "sim.log",
        )
    return _check_results(results, build_dir / "sim.log")


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
