"""Reading a YAML spec as located nodes, checked against the format of `rfc.spec.schema`.

ruamel.yaml composes the document into nodes that carry their start marks; rfc keeps those
nodes (rather than the plain values) so that every error can name the file, line and column of
the element responsible.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

from ruamel.yaml import YAML
from ruamel.yaml.error import MarkedYAMLError, YAMLError
from ruamel.yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from rfc.errors import RfcError, SourceLocation, did_you_mean
from rfc.spec.schema import Key, Section, ValueKind

_KIND_NAMES = {
    "tag:yaml.org,2002:str": ValueKind.STRING,
    "tag:yaml.org,2002:int": ValueKind.INTEGER,
    "tag:yaml.org,2002:float": ValueKind.NUMBER,
    "tag:yaml.org,2002:bool": ValueKind.BOOLEAN,
}


@dataclass(frozen=True)
class YamlNode:
    """One node of the spec document and where it starts."""

    node: Node
    file: str
    loader: YAML

    @property
    def location(self) -> SourceLocation:
        """File, 1-based line and column of the node's first character."""
        mark = self.node.start_mark
        return SourceLocation(self.file, mark.line + 1, mark.column + 1)

    @property
    def kind(self) -> ValueKind | None:
        """The node's kind, or None for null."""
        if isinstance(self.node, MappingNode):
            return ValueKind.MAPPING
        if isinstance(self.node, SequenceNode):
            return ValueKind.LIST
        return _KIND_NAMES.get(str(self.node.tag))

    def describe(self) -> str:
        """Name the node's kind for an error: ``a string ('64 bits')``, ``a mapping``."""
        kind = self.kind
        if kind is None:
            return "empty (null)"
        if isinstance(self.node, ScalarNode):
            return f"{kind.value} ('{self.node.value}')"
        return kind.value

    @cached_property
    def value(self) -> Any:
        """The Python value of a scalar node."""
        return self.loader.constructor.construct_object(self.node, deep=True)

    def child(self, node: Node) -> YamlNode:
        """Wrap a node of the same document."""
        return YamlNode(node, self.file, self.loader)

    def elements(self) -> Iterator[YamlNode]:
        """The elements of a list node."""
        for node in self.node.value:
            yield self.child(node)

    def pairs(self) -> Iterator[tuple[YamlNode, YamlNode]]:
        """The keys and values of a mapping node."""
        for key, value in self.node.value:
            yield self.child(key), self.child(value)


def load_yaml(path: Path, display: str) -> YamlNode:
    """Parse a spec file into its root node.

    Args:
        path: The file to read.
        display: How to name the file in messages (as the user gave it).

    Raises:
        RfcError: The file is unreadable, empty or not valid YAML.
    """
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise RfcError(f"cannot read spec '{display}': {exc}") from None
    loader = YAML(typ="safe")  # libyaml's parser when ruamel.yaml.clib is there: 3x faster
    try:
        node = loader.compose(text)
    except YAMLError:
        node = _compose_pure(text, display)  # the pure parser words errors the same everywhere
    if node is None:
        raise RfcError(
            f"spec '{display}' is empty",
            location=SourceLocation(display, 1, 1),
            hint="start from 'project:', 'accelerators:' and 'blocks:' (see docs/spec.md)",
        )
    return YamlNode(node, display, loader)


def _compose_pure(text: str, display: str) -> Node | None:
    """Parse with ruamel's pure-Python parser, turning its error into an `RfcError`."""
    try:
        node: Node | None = YAML(typ="safe", pure=True).compose(text)
        return node
    except MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        where = SourceLocation(display, mark.line + 1, mark.column + 1) if mark else None
        problem = exc.problem or exc.context or "not valid YAML"
        raise RfcError(f"YAML syntax error: {problem}", location=where) from None
    except YAMLError as exc:
        raise RfcError(f"YAML syntax error in '{display}': {exc}") from None


class MappingReader:
    """The keys of one mapping, checked against its section of the format.

    Unknown and duplicate keys, missing required keys and values of the wrong kind are errors
    raised by the constructor, so that the front-end only sees well-formed values.

    Args:
        node: The mapping node.
        section: Its section of the format.
        owner: How to name the mapping in messages (``a block``).
        named: When given and the mapping has a string ``name``, the mapping is called
            ``<named> '<name>'`` instead (``block 'Euler_pub'``).
    """

    def __init__(
        self, node: YamlNode, section: Section, owner: str, named: str | None = None
    ) -> None:
        expect_kind(node, (ValueKind.MAPPING,), owner)
        self.node = node
        self.section = section
        self.owner = _owner(node, owner, named)
        self.keys: dict[str, YamlNode] = {}
        self.values: dict[str, YamlNode] = {}
        for key_node, value_node in node.node.value:
            key, value = node.child(key_node), node.child(value_node)
            name = str(key.value) if isinstance(key_node, ScalarNode) else "?"
            if name not in section.names:
                raise RfcError(
                    f"unknown key '{name}' in {owner}; expected one of {', '.join(section.names)}",
                    location=key.location,
                    hint=did_you_mean(name, section.names),
                )
            if name in self.keys:
                raise RfcError(
                    f"key '{name}' appears twice in {self.owner} "
                    f"(first at {self.keys[name].location})",
                    location=key.location,
                )
            expect_kind(value, section.key(name).kinds, f"'{name}' of {self.owner}")
            self.keys[name], self.values[name] = key, value
        for expected in section.keys:
            if expected.required and expected.name not in self.values:
                raise RfcError(
                    f"{self.owner} has no '{expected.name}', which is required: "
                    f"{expected.description.rstrip('.')}",
                    location=node.location,
                )

    def has(self, name: str) -> bool:
        """Whether the key is present."""
        return name in self.values

    def node_of(self, name: str) -> YamlNode:
        """The value node of a present key."""
        return self.values[name]

    def location(self, name: str) -> SourceLocation:
        """Where the key's value is written, or the mapping when the key is absent."""
        return self.values[name].location if name in self.values else self.node.location

    def get(self, name: str, default: Any = None) -> Any:
        """The scalar value of a key, or `default` when absent."""
        return self.values[name].value if name in self.values else default

    def strings(self, name: str) -> list[tuple[str, SourceLocation]]:
        """A string-or-list-of-strings key as (value, location) pairs; empty when absent."""
        if name not in self.values:
            return []
        node = self.values[name]
        if node.kind is ValueKind.STRING:
            return [(node.value, node.location)]
        return [(item.value, item.location) for item in node.elements()]

    def choice(self, name: str, default: str | None = None) -> str | None:
        """A string key restricted to its choices (case-insensitive), in canonical spelling."""
        if name not in self.values:
            return default
        key = self.section.key(name)
        return pick(self.values[name], key, f"'{name}' of {self.owner}")

    def items(self, name: str) -> Iterator[YamlNode]:
        """The elements of a list key (none when absent)."""
        if name in self.values:
            yield from self.values[name].elements()


def _owner(node: YamlNode, owner: str, named: str | None) -> str:
    if named is None:
        return owner
    for key, value in node.node.value:
        if key.value == "name" and isinstance(value, ScalarNode):
            name = node.child(value)
            if name.kind is ValueKind.STRING:
                return f"{named} '{name.value}'"
    return owner


def pick(node: YamlNode, key: Key, what: str) -> str:
    """Return the canonical spelling of a choice, or raise naming the valid ones."""
    text = str(node.value)
    for choice in key.choices:
        if str(choice).lower() == text.lower():
            return str(choice)
    options = [str(c) for c in key.choices]
    raise RfcError(
        f"{what} must be one of {', '.join(options)}, not '{text}'",
        location=node.location,
        hint=did_you_mean(text, options),
    )


def expect_kind(node: YamlNode, kinds: tuple[ValueKind, ...], what: str) -> None:
    """Raise unless the node is of one of the kinds (lists of strings checked item by item)."""
    kind = node.kind
    if kind in kinds or (kind is ValueKind.INTEGER and ValueKind.NUMBER in kinds):
        return
    if kind is ValueKind.MAPPING and ValueKind.COUNTS in kinds:
        for key, value in node.pairs():
            if value.kind is not ValueKind.INTEGER:
                raise RfcError(
                    f"{what} must map field paths to integers, but '{key.value}' maps to "
                    f"{value.describe()}",
                    location=value.location,
                )
        return
    if kind is ValueKind.LIST and ValueKind.STRING_LIST in kinds:
        for item in node.elements():
            if item.kind is not ValueKind.STRING:
                raise RfcError(
                    f"{what} must be a list of strings, but an element is {item.describe()}",
                    location=item.location,
                )
        return
    expected = " or ".join(k.value for k in kinds)
    raise RfcError(f"{what} must be {expected}, not {node.describe()}", location=node.location)
