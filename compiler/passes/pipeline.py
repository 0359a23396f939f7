"""The pipeline as a visible tuple, and its driver (which verifies after every pass)."""

from __future__ import annotations

from collections.abc import Callable

from rfc.ir.model import Design
from rfc.ir.verify import verify
from rfc.passes.base import Pass
from rfc.passes.check_connections import CheckConnections
from rfc.passes.check_hardware import CheckHardware
from rfc.passes.check_timing import CheckTiming
from rfc.passes.derive_infrastructure import DeriveInfrastructure
from rfc.passes.expand_selections import ExpandSelections
from rfc.passes.flatten_messages import FlattenMessages
from rfc.passes.resolve_scheduler import ResolveScheduler
from rfc.passes.resolve_types import ResolveTypes

#: The passes that derive the holistic model from a spec.
MODEL_PIPELINE: tuple[Pass, ...] = (
    ResolveTypes(),
    CheckConnections(),
    ExpandSelections(),
    FlattenMessages(),
    DeriveInfrastructure(),
)
#: `rfc check`'s: the model, then the rules its logic must obey.
PIPELINE: tuple[Pass, ...] = (*MODEL_PIPELINE, CheckHardware(), CheckTiming())
#: `rfc build`'s pipeline: the scheduler left to the DSE is chosen too (`rfc check` skips it).
BUILD_PIPELINE: tuple[Pass, ...] = (*PIPELINE, ResolveScheduler())
#: `rfc build --no-hardware`'s: no logic is made, so its rules are not applied.
SOFTWARE_BUILD_PIPELINE: tuple[Pass, ...] = (*MODEL_PIPELINE, ResolveScheduler())
#: The name of the front-end's output, accepted wherever a pass name is (``--dump-ir-after``).
PARSE = "parse"


def pass_names(pipeline: tuple[Pass, ...] = PIPELINE) -> tuple[str, ...]:
    """The pass names in pipeline order, after ``parse`` (the front-end)."""
    return (PARSE, *(p.name for p in pipeline))


def describe(pipeline: tuple[Pass, ...] = PIPELINE) -> str:
    """The pipeline in one line: ``resolve-types → check-connections → ...``."""
    return " → ".join(p.name for p in pipeline)


def run_pipeline(
    design: Design,
    pipeline: tuple[Pass, ...] = PIPELINE,
    after: Callable[[str, Design], None] | None = None,
) -> Design:
    """Run the passes in order, verifying the design after the front-end and every pass.

    Args:
        design: A design from a front-end.
        pipeline: The passes to run.
        after: Called with each pass name (``parse`` first) and the design it produced.

    Raises:
        RfcError: The spec is wrong; the message points at the element at fault.
        IrInvariantError: A pass broke an invariant (a bug in rfc).
    """
    verify(design)
    if after is not None:
        after(PARSE, design)
    for step in pipeline:
        design = step.apply(design)
        verify(design)
        if after is not None:
            after(step.name, design)
    return design
