"""Pass-through logic: each subscriber's messages come back unchanged from one publisher.

The paper's multi-type system (§7.1.3) puts a pass-through accelerator between each subscriber
and its publisher; its logic then returns every PS→PL message as a PL→PS message of the
publisher the chain leads to. `pass_through_routes` finds those chains in a design, and
`PassThroughLogic` is the logic as a Python model — optionally cutting messages into several
chunks, as a preemptive scheduler does. Tests use it as the reference for simulated fixture
logic, and `rfc.runtime.timing` for the queue-policy measurement.
"""

from __future__ import annotations

from collections.abc import Mapping

from rfc.ir.infrastructure import Infrastructure
from rfc.ir.model import Design
from rfc.runtime.protocol import Chunk, split_message


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


class PassThroughLogic:
    """The logic of a pass-through system, as a `LogicModel`.

    Args:
        routes: Publisher id for each subscriber id.
        cut: Cut PL→PS messages into chunks of at most this many payload bytes (0: never);
            continuation chunks carry END only when they finish the message, as the protocol
            allows.
    """

    def __init__(self, routes: Mapping[int, int], cut: int = 0) -> None:
        self.routes = dict(routes)
        self.cut = cut

    def transfer(self, transfer: bytes) -> list[bytes]:
        """Answer one PS→PL chunk with the publisher's chunk(s); unknown ids are dropped."""
        chunk = Chunk.from_bytes(transfer)
        publisher = self.routes.get(chunk.id)
        if publisher is None:
            return []
        payload = chunk.payload
        if not self.cut or len(payload) <= self.cut:
            sizes = [len(payload)]
        else:
            sizes = [self.cut] * (len(payload) // self.cut)
            if len(payload) % self.cut:
                sizes.append(len(payload) % self.cut)
        return [piece.to_bytes() for piece in split_message(publisher, payload, sizes)]
