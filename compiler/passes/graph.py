"""Graph checks of check-connections: no cycle, every block between a subscriber and a publisher."""

from __future__ import annotations

from collections import deque

from rfc.errors import RfcError
from rfc.ir.model import Block, BlockKind, Connection


def check_graph(blocks: tuple[Block, ...], connections: tuple[Connection, ...]) -> None:
    """Raise on a cycle, a block no subscriber reaches, or a block that reaches no publisher."""
    successors: dict[str, list[Connection]] = {b.name: [] for b in blocks}
    predecessors: dict[str, list[str]] = {b.name: [] for b in blocks}
    for connection in connections:
        successors[connection.source.block].append(connection)
        predecessors[connection.destination.block].append(connection.source.block)
    _check_acyclic(blocks, successors)
    reached = _reach(
        [b.name for b in blocks if b.kind is BlockKind.SUBSCRIBER],
        {name: [c.destination.block for c in out] for name, out in successors.items()},
    )
    for block in blocks:
        if block.name not in reached:
            raise RfcError(
                f"block '{block.name}' is unreachable: no connection leads to it from a subscriber",
                location=block.location,
            )
    useful = _reach([b.name for b in blocks if b.kind is BlockKind.PUBLISHER], predecessors)
    for block in blocks:
        if block.name in useful:
            continue
        if block.kind is BlockKind.SUBSCRIBER and not successors[block.name]:
            raise RfcError(
                f"subscriber '{block.name}' sends its messages to no block",
                location=block.location,
                hint="add an 'outgoing' entry (YAML) or connect it with >> (Python)",
            )
        raise RfcError(
            f"block '{block.name}' is a dead end: nothing it sends reaches a publisher",
            location=block.location,
            hint="connect its outputs towards a publisher, or remove it",
        )


def _reach(starts: list[str], edges: dict[str, list[str]]) -> set[str]:
    seen = set(starts)
    queue = deque(starts)
    while queue:
        for following in edges[queue.popleft()]:
            if following not in seen:
                seen.add(following)
                queue.append(following)
    return seen


def _check_acyclic(blocks: tuple[Block, ...], successors: dict[str, list[Connection]]) -> None:
    """Depth-first search; a connection back into the current path closes a cycle."""
    done: set[str] = set()
    for root in blocks:
        if root.name in done:
            continue
        path = [root.name]
        stack = [iter(successors[root.name])]
        on_path = {root.name}
        while stack:
            connection = next(stack[-1], None)
            if connection is None:
                stack.pop()
                done.add(path[-1])
                on_path.discard(path.pop())
                continue
            target = connection.destination.block
            if target in on_path:
                loop = [*path[path.index(target) :], target]
                raise RfcError(
                    f"cycle: {' → '.join(loop)}; data must flow from subscribers to publishers "
                    "without loops",
                    location=connection.location,
                )
            if target not in done:
                path.append(target)
                on_path.add(target)
                stack.append(iter(successors[target]))
