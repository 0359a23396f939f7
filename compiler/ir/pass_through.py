"""Pass-through chains: the logic of a design that only forwards each subscriber's messages.

The paper's multi-type system (§7.1.3) puts a pass-through accelerator between each subscriber
and its publisher. `pass_through_routes` finds those chains in the holistic model; the runtime's
`rfc.runtime.loopback.PassThroughLogic` then plays that logic from the routes alone.
"""

from __future__ import annotations

from rfc.ir.infrastructure import Infrastructure
from rfc.ir.model import Design


class NotPassThroughError(ValueError):
    """The logic of a design is not made of pass-through chains."""


def pass_through_routes(design: Design) -> dict[int, int]:
    """Map each subscriber id in the logic to the publisher id its pass-through chain reaches.

    Every hardware path from a subscriber must run through accelerators of one input and one
    output of the subscriber's message type, without fan-out, to one publisher.

    Raises:
        NotPassThroughError: The logic is something else.
    """
    infrastructure = design.infrastructure
    assert isinstance(infrastructure, Infrastructure)
    successors: dict[str, list[str]] = {}
    for connection in infrastructure.hardware_connections:
        successors.setdefault(connection.source.block, []).append(connection.destination.block)
    publishers = {c.block: c for c in infrastructure.publishers}
    routes = {}
    for subscriber in infrastructure.subscribers:
        block, seen = subscriber.block, []
        while block not in publishers:
            following = successors.get(block, [])
            if len(following) != 1 or block in seen:
                raise NotPassThroughError(f"{block} does not lead to one publisher")
            seen.append(block)
            block = following[0]
        if publishers[block].message != subscriber.message:
            raise NotPassThroughError(f"{subscriber.block} and {block} differ in type")
        routes[subscriber.id] = publishers[block].id
    return routes
