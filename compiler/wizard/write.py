"""Putting a wizard's system on disk: the spec and its stubs, checked as `rfc check` checks.

Nothing stays half-written: when the check fails, every file the wizard created is removed and
the error is raised; files that existed before (an accelerator's sources) are never touched.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from rfc.errors import RfcError
from rfc.ir.model import Design
from rfc.wizard.emit import to_python, to_yaml
from rfc.wizard.model import SystemAnswers
from rfc.wizard.stub import reference_stub


@dataclass(frozen=True)
class Written:
    """What a wizard session wrote: the spec, the stubs, and the checked design."""

    spec: Path
    stubs: tuple[Path, ...]
    design: Design


def spec_text(system: SystemAnswers, spec: Path) -> str:
    """The spec in the form its suffix asks for (``.py``: Python, else YAML)."""
    return to_python(system) if spec.suffix == ".py" else to_yaml(system)


def write_stubs(system: SystemAnswers, base: Path) -> tuple[Path, ...]:
    """Write the reference stub of every ROS-SW accelerator whose reference file is missing."""
    written = []
    for accelerator in system.accelerators:
        if accelerator.kind != "ROS-SW" or not accelerator.reference:
            continue
        path = base / accelerator.reference.rpartition(":")[0]
        if path.exists() or path in written:
            continue
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(reference_stub(accelerator), encoding="utf-8")
        written.append(path)
    return tuple(written)


def check_draft(system: SystemAnswers, spec: Path) -> Design:
    """Compile `system` as `rfc build` does, from a draft beside `spec`.

    The draft sits beside the spec so that relative paths hold; it and the stubs written for
    it are removed again.
    """
    from rfc.driver import compile_spec
    from rfc.passes.pipeline import BUILD_PIPELINE

    draft = spec.with_name(f".rfc-wizard-draft{spec.suffix}")
    stubs = write_stubs(system, spec.parent)
    try:
        draft.write_text(spec_text(system, spec), encoding="utf-8")
        return compile_spec(draft, pipeline=BUILD_PIPELINE)
    finally:
        for path in (draft, *stubs):
            path.unlink(missing_ok=True)


def write_system(system: SystemAnswers, spec: Path) -> Written:
    """Write the stubs and the spec, and check the spec; on error leave nothing behind.

    Raises:
        RfcError: The spec does not pass `rfc check` (nothing is left written).
    """
    from rfc.driver import compile_spec

    if spec.suffix not in (".yaml", ".yml", ".py"):
        raise RfcError(
            f"cannot write a spec to '{spec}'; expected a .yaml or .py file",
            hint="name the output project.yaml or project.py",
        )
    spec.parent.mkdir(parents=True, exist_ok=True)
    stubs = write_stubs(system, spec.parent)
    created = (*stubs, spec)
    try:
        spec.write_text(spec_text(system, spec), encoding="utf-8")
        design = compile_spec(spec)
    except BaseException:
        for path in created:
            path.unlink(missing_ok=True)
        raise
    return Written(spec, stubs, design)
