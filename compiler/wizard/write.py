"""Putting a wizard's system on disk: the spec and its stubs, checked as `rfc check` checks.

Nothing stays half-written: when the check fails, every file the wizard created is removed and
the error is raised; files that existed before (an accelerator's sources) are never touched.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

from rfc.errors import RfcError
from rfc.ir.model import Design
from rfc.wizard.emit import to_python, to_yaml
from rfc.wizard.model import SystemAnswers
from rfc.wizard.stub import passes_through, reference_stub


@dataclass(frozen=True)
class Written:
    """What a wizard session wrote: the spec, the stubs, and the checked design."""

    spec: Path
    stubs: tuple[Path, ...]
    design: Design


def spec_text(system: SystemAnswers, spec: Path) -> str:
    """The spec in the form its suffix asks for (``.py``: Python, else YAML)."""
    return to_python(system) if spec.suffix == ".py" else to_yaml(system)


def write_stubs(system: SystemAnswers, spec: Path) -> tuple[Path, ...]:
    """Write the skeleton of every accelerator that asks for one, into its missing source.

    A ROS-SW accelerator whose output is its input's type gets a pass-through reference stub
    (so the system runs end to end at once); the others get `rfc stub`'s typed skeleton.
    """
    from rfc.lower.stubs import StubLanguage, accelerator_stub
    from rfc.spec.common import sources_may_be_missing

    wanted = [a for a in system.accelerators if a.skeleton]
    if not wanted:
        return ()
    # the references of those accelerators live in the files still to be written
    draft = replace(
        system,
        accelerators=tuple(
            replace(a, reference="") if a.skeleton else a for a in system.accelerators
        ),
    )
    with sources_may_be_missing():
        design = _compile(draft, spec, build=False)
    written: list[Path] = []
    for accelerator in wanted:
        path = spec.parent / accelerator.sources
        if path.exists():
            continue
        if passes_through(accelerator):
            text = reference_stub(accelerator)
        else:
            language = {
                "ROS-SW": StubLanguage.PYTHON,
                "VHDL": StubLanguage.VHDL,
                "HLS": StubLanguage.HLS,
            }.get(accelerator.kind, StubLanguage.MYHDL)
            text = accelerator_stub(design, accelerator.name, language)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        written.append(path)
    return tuple(written)


def _compile(system: SystemAnswers, spec: Path, *, build: bool) -> Design:
    """Compile `system` from a draft beside `spec` (so relative paths hold), then remove it."""
    from rfc.driver import compile_spec
    from rfc.passes.pipeline import BUILD_PIPELINE, PIPELINE

    draft = spec.with_name(f".rfc-wizard-draft{spec.suffix}")
    try:
        draft.write_text(spec_text(system, spec), encoding="utf-8")
        return compile_spec(draft, pipeline=BUILD_PIPELINE if build else PIPELINE)
    except RfcError as exc:  # the spec would hold the same text: point at its line
        if exc.location is None or exc.location.file != str(draft):
            raise
        location = replace(exc.location, file=str(spec))
        raise RfcError(exc.message, location=location, hint=exc.hint) from None
    finally:
        draft.unlink(missing_ok=True)


def check_draft(system: SystemAnswers, spec: Path) -> Design:
    """Compile `system` as `rfc build` does (scheduler chosen), with its skeletons for a while.

    The draft spec and the skeletons written for it are removed again.
    """
    stubs = write_stubs(system, spec)
    try:
        return _compile(system, spec, build=True)
    finally:
        for path in stubs:
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
    stubs = write_stubs(system, spec)
    created = (*stubs, spec)
    try:
        spec.write_text(spec_text(system, spec), encoding="utf-8")
        design = compile_spec(spec)
    except BaseException:
        for path in created:
            path.unlink(missing_ok=True)
        raise
    return Written(spec, stubs, design)
