"""resolve-scheduler: `scheduler: {algorithm: auto}` becomes the scheduler the DSE recommends.

Runs after derive-infrastructure in `rfc build` (not in `rfc check`, which stays fast). With
every publisher's period known, the project's traffic is simulated under each candidate and
ranked by `objective` (`rfc.dse.project`, the same ranking `rfc dse SPEC` prints). Without
periods nothing can be simulated: one publisher gets PFP (every algorithm serves a lone input
alike; fixed priority is the smallest), several get LRU, the only algorithm that serves every
requester within N-1 transfers whatever the timing. An explicit algorithm is kept.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import ClassVar

from rfc.ir.model import Design


@dataclass(frozen=True)
class ResolveScheduler:
    """Replace an ``auto`` scheduler by the recommended one, with the reason recorded.

    Attributes:
        objective: The ranking criteria, as `rfc dse --objective` takes them.
    """

    name: ClassVar[str] = "resolve-scheduler"
    objective: str = "completed,missed,max_lateness,lut"

    def apply(self, design: Design) -> Design:
        """Return the design with a concrete scheduler algorithm."""
        infrastructure = design.infrastructure
        assert infrastructure is not None
        scheduler = infrastructure.scheduler
        if scheduler.algorithm != "auto":
            return design
        inputs = scheduler.inputs
        if len(inputs) >= 2 and all(i.period is not None for i in inputs):
            from rfc.dse.objective import parse_objective
            from rfc.dse.project import project_traffic, recommend

            traffic = project_traffic(design.project.name, inputs)
            recommendation = recommend(traffic, parse_objective(self.objective))
            algorithm = recommendation.scheduler
            reason = "rfc dse: " + "; ".join(recommendation.reasons)
        elif len(inputs) <= 1:
            algorithm = "PFP"
            reason = "one publisher: every algorithm serves it alike; fixed priority is smallest"
        else:
            algorithm = "LRU"
            reason = (
                "no period on every publisher, so nothing to simulate: LRU serves every "
                "requester within N-1 transfers whatever the timing"
            )
        resolved = replace(scheduler, algorithm=algorithm, reason=reason)
        return replace(design, infrastructure=replace(infrastructure, scheduler=resolved))
