"""Pass-through logic: each subscriber's messages come back unchanged from one publisher.

The paper's multi-type system (§7.1.3) puts a pass-through accelerator between each subscriber
and its publisher; its logic then returns every PS→PL message as a PL→PS message of the
publisher the chain leads to. `PassThroughLogic` is that logic as a Python model, given the
routes (`rfc.ir.pass_through.pass_through_routes` finds them in a design) — optionally cutting
messages into several chunks, as a preemptive scheduler does. Tests use it as the reference for
simulated fixture logic.
"""

from __future__ import annotations

from collections.abc import Mapping

from rfc.runtime.protocol import Chunk, split_message


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
