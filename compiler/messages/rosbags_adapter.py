"""The one place rfc talks to rosbags: message definitions, (de)serialization and bags.

rosbags is rfc's only source of message definitions and its oracle for serialization. Everything
else in rfc sees the neutral `FieldDef` description below, so that no other module depends on
rosbags' tuples, and so that a rosbags upgrade touches one file.
"""

from __future__ import annotations

import tempfile
from collections.abc import Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
from rosbags.interfaces import Connection, MessageDefinitionFormat, Nodetype
from rosbags.rosbag1 import Reader as Rosbag1Reader
from rosbags.rosbag1 import ReaderError as Rosbag1ReaderError
from rosbags.rosbag1 import Writer as Rosbag1Writer
from rosbags.rosbag1 import WriterError as Rosbag1WriterError
from rosbags.rosbag2 import Reader as Rosbag2Reader
from rosbags.rosbag2 import ReaderError as Rosbag2ReaderError
from rosbags.rosbag2 import StoragePlugin, WriterError
from rosbags.rosbag2 import Writer as Rosbag2Writer
from rosbags.serde import SerdeError
from rosbags.typesys import (
    Stores,
    TypesysError,
    get_types_from_idl,
    get_types_from_msg,
    get_typestore,
)
from rosbags.typesys.base import normalize_fieldname
from rosbags.typesys.store import Typestore

from rfc.errors import RfcError, closest, did_you_mean

# The layout's data model owns these (the runtime reads it too); re-exported for the front-end.
from rfc.messages.layout_model import PRIMITIVE_DTYPES as PRIMITIVE_DTYPES
from rfc.messages.layout_model import PRIMITIVE_SIZES as PRIMITIVE_SIZES
from rfc.messages.layout_model import Middleware as Middleware

DEFAULT_DISTRO = {Middleware.ROS1: "noetic", Middleware.ROS2: "humble"}
DISTROS = {
    Middleware.ROS1: ("noetic",),
    Middleware.ROS2: (
        "dashing",
        "eloquent",
        "foxy",
        "galactic",
        "humble",
        "iron",
        "jazzy",
        "kilted",
        "lyrical",
    ),
}

#: The member rosbags gives messages without fields (ROS 2's IDL needs one; ROS 1 sends nothing).
_EMPTY_PLACEHOLDER = "structure_needs_at_least_one_member"


@dataclass(frozen=True)
class FieldDef:
    """One field of a message definition, as written in the .msg file.

    Attributes:
        name: The field's name in the definition.
        base: A primitive name, ``string``, or the canonical name of a message type.
        is_message: Whether `base` is a message type.
        array_length: Element count of a fixed-size array (``float64[9]``), else None.
        is_sequence: Whether the field is a variable-length sequence (``float64[]``).
        sequence_bound: Maximum element count of a bounded sequence, 0 when unbounded.
        string_bound: Maximum length of a bounded string, 0 when unbounded.
    """

    name: str
    base: str
    is_message: bool
    array_length: int | None = None
    is_sequence: bool = False
    sequence_bound: int = 0
    string_bound: int = 0


def attribute_name(field_name: str) -> str:
    """Return the Python attribute under which rosbags stores a field (keywords get a suffix)."""
    return normalize_fieldname(field_name)


def canonical_name(name: str) -> str:
    """Turn ``pkg/Name`` into rosbags' canonical ``pkg/msg/Name``; leave other forms alone."""
    parts = name.strip("/").split("/")
    if len(parts) == 2:
        return f"{parts[0]}/msg/{parts[1]}"
    return "/".join(parts)


class MessageTypes:
    """The message definitions visible to one middleware: a rosbags store plus the user's own.

    Args:
        middleware: ROS 1 (the noetic store) or ROS 2 (one of the ROS 2 distributions).
        distro: Store to start from; defaults to noetic for ROS 1 and humble for ROS 2.
        msg_paths: Directories searched for ``<package>/msg/<Name>.msg`` definitions.
        bags: Bags whose embedded definitions are added (ROS 2 mcap/db3, ROS 1 bag).

    Raises:
        RfcError: An unknown distro, a missing directory or bag, or a definition that does not
            parse or refers to a type nobody defines.
    """

    def __init__(
        self,
        middleware: Middleware | str = Middleware.ROS2,
        distro: str | None = None,
        msg_paths: Sequence[str | Path] = (),
        bags: Sequence[str | Path] = (),
    ) -> None:
        self.middleware = Middleware(middleware)
        self.distro = distro or DEFAULT_DISTRO[self.middleware]
        if self.distro not in DISTROS[self.middleware]:
            raise RfcError(
                f"unknown {self.middleware.label} distro '{self.distro}'; expected one "
                f"of {', '.join(DISTROS[self.middleware])}",
                hint=did_you_mean(self.distro, DISTROS[self.middleware]),
            )
        self._store: Typestore = get_typestore(Stores(f"{self.middleware.value}_{self.distro}"))
        self._fields: dict[str, tuple[FieldDef, ...]] = {}
        self.cache: dict[Any, Any] = {}
        """Results derived from these definitions (layouts), kept with them."""
        self.unresolved: dict[str, str] = {}
        """Types whose definitions need a type nobody defines, with the reason; only using
        them is an error."""
        found: dict[str, tuple[dict[str, Any], str]] = {}
        for bag in bags:
            found.update(_definitions_in_bag(Path(bag), self._store))
        for directory in msg_paths:  # the user's own definitions win over a bag's
            found.update(_definitions_in_directory(Path(directory)))
        self._register(found)

    def _register(self, found: dict[str, tuple[Any, str]]) -> None:
        """Register every definition whose references resolve, in any order of sources."""
        known = set(self._store.fielddefs) | set(found)
        missing: dict[str, str] = {}
        for name, (definition, origin) in found.items():
            for field_name, desc in definition[1]:
                ref = next((r for r in _referenced_types(desc) if r not in known), None)
                if ref is not None:
                    missing[name] = (
                        f"{origin}: {name} field '{field_name}' has type '{ref}', which no "
                        "definition provides"
                    )
        while True:  # a type that uses an unresolved one is unresolved too
            more = {
                name: f"{found[name][1]}: {name} uses {ref}, which is unresolved"
                for name in found.keys() - missing.keys()
                for _, desc in found[name][0][1]
                for ref in _referenced_types(desc)
                if ref in missing
            }
            if not more:
                break
            missing.update(more)
        self.unresolved = missing
        try:
            self._store.register(
                {name: definition for name, (definition, _) in found.items() if name not in missing}
            )
        except TypesysError as exc:
            raise RfcError(str(exc)) from None

    def names(self) -> list[str]:
        """Return every canonical type name, sorted."""
        return sorted(self._store.fielddefs)

    def resolve(self, name: str) -> str:
        """Return the canonical name (``pkg/msg/Name``) of a type given in any usual spelling.

        Raises:
            RfcError: No such type; the message suggests the closest names.
        """
        canonical = canonical_name(name)
        if canonical in self._store.fielddefs:
            return canonical
        if canonical in self.unresolved:
            raise RfcError(
                f"message type '{name}' cannot be used: {self.unresolved[canonical]}",
                hint="add the directory that defines it with --msg-path",
            )
        known = self.names()
        # Match in the user's own spelling (Name, pkg/Name or pkg/msg/Name), suggest full names.
        parts = name.strip("/").count("/") + 1
        spelled = {1: lambda n: n.rsplit("/", 1)[-1], 2: _short_name}.get(parts, lambda n: n)
        by_spelling: dict[str, list[str]] = {}
        for known_name in known:
            by_spelling.setdefault(spelled(known_name), []).append(known_name)
        matches = [n for key in closest(name, by_spelling) for n in by_spelling[key]]
        shown = [n if parts == 3 else _short_name(n) for n in matches[:3]]
        own = "add the directory of your own .msg/.idl files with --msg-path"
        suggestion = "did you mean " + " or ".join(f"'{n}'" for n in shown) + "?"
        package = canonical.split("/")[0]
        if not shown:
            hint = own
        elif any(n.startswith(f"{package}/") for n in known):
            hint = suggestion
        else:  # a package no store knows: most likely the user's own
            hint = f"{suggestion} If it is your own type, {own}"
        raise RfcError(
            f"unknown message type '{name}' for {self.middleware.label} {self.distro}",
            hint=hint,
        )

    def definition(self, canonical: str) -> tuple[str, str]:
        """The type's definition with every type it uses, as one text, and its ROS 1 MD5 sum."""
        version = 1 if self.middleware is Middleware.ROS1 else 2
        return self._store.generate_msgdef(canonical, ros_version=version)

    def display_name(self, canonical: str) -> str:
        """Spell a type the way its middleware does: ``pkg/Name`` (ROS 1), ``pkg/msg/Name``."""
        return _short_name(canonical) if self.middleware is Middleware.ROS1 else canonical

    def fields(self, canonical: str) -> tuple[FieldDef, ...]:
        """Return the fields of a type in serialization order."""
        if canonical not in self._fields:
            _, raw = self._store.fielddefs[canonical]
            self._fields[canonical] = tuple(
                _field_def(name, desc)
                for name, desc in raw
                # rosbags models empty messages as ROS 2 does; on the ROS 1 wire they are empty.
                if not (self.middleware is Middleware.ROS1 and name == _EMPTY_PLACEHOLDER)
            )
        return self._fields[canonical]

    def serialize(self, message: object, canonical: str) -> bytes:
        """Serialize with rosbags: CDR (with its 4-byte header) for ROS 2, ROS 1 otherwise."""
        if self.middleware is Middleware.ROS2:
            return bytes(self._store.serialize_cdr(message, canonical, little_endian=True))
        return bytes(self._store.serialize_ros1(message, canonical))

    def deserialize(self, data: bytes | memoryview, canonical: str) -> object:
        """Deserialize with rosbags; raises RfcError on bytes that are not a valid message."""
        try:
            if self.middleware is Middleware.ROS2:
                return self._store.deserialize_cdr(data, canonical)
            return self._store.deserialize_ros1(data, canonical)
        except SerdeError as exc:
            raise RfcError(f"not a valid {canonical} message: {exc}") from None

    def build(self, canonical: str, tree: Mapping[str, Any]) -> object:
        """Build a rosbags message object from a nested dict of field name → value.

        Sub-messages are nested dicts, arrays and sequences plain lists; primitive arrays become
        NumPy arrays of the dtype rosbags uses. A field left out takes its default: zero,
        false, an empty string or sequence.
        """
        cls = self._store.types[canonical]
        kwargs = {}
        for field in self.fields(canonical):
            value = tree[field.name] if field.name in tree else _default(field)
            if field.array_length is not None or field.is_sequence:
                if field.is_message:
                    value = [self.build(field.base, item) for item in value]
                elif field.base != "string":
                    value = np.asarray(value, dtype=PRIMITIVE_DTYPES[field.base])
                else:
                    value = list(value)
            elif field.is_message:
                value = self.build(field.base, value)
            kwargs[attribute_name(field.name)] = value
        return cls(**kwargs)


def _default(field: FieldDef) -> Any:
    """The value of a field left out of a tree: zero, false, empty; sub-messages likewise."""
    if field.is_sequence:
        return []
    if field.is_message:
        one: Any = {}
    elif field.base == "string":
        one = ""
    elif field.base == "bool":
        one = False
    elif field.base.startswith("float"):
        one = 0.0
    else:
        one = 0
    return one if field.array_length is None else [one] * field.array_length


def _short_name(canonical: str) -> str:
    return canonical.replace("/msg/", "/", 1)


def _field_def(name: str, desc: tuple[Any, Any]) -> FieldDef:
    kind, detail = desc
    if kind == Nodetype.BASE:
        return FieldDef(name, _primitive(name, detail[0]), False, string_bound=detail[1])
    if kind == Nodetype.NAME:
        return FieldDef(name, detail, True)
    (sub_kind, sub_detail), count = detail
    is_message = sub_kind == Nodetype.NAME
    base = sub_detail if is_message else _primitive(name, sub_detail[0])
    string_bound = 0 if is_message else sub_detail[1]
    if kind == Nodetype.ARRAY:
        return FieldDef(name, base, is_message, array_length=count, string_bound=string_bound)
    return FieldDef(
        name, base, is_message, is_sequence=True, sequence_bound=count, string_bound=string_bound
    )


def _primitive(field_name: str, base: str) -> str:
    if base != "string" and base not in PRIMITIVE_SIZES:
        raise RfcError(
            f"field '{field_name}' has type '{base}', which rosbags cannot serialize",
            hint=f"exclude '{field_name}' or use a type such as float64 or string",
        )
    return base


def _referenced_types(desc: tuple[Any, Any]) -> Iterator[str]:
    kind, detail = desc
    if kind == Nodetype.NAME:
        yield detail
    elif kind in (Nodetype.ARRAY, Nodetype.SEQUENCE):
        yield from _referenced_types(detail[0])


def _definitions_in_directory(directory: Path) -> dict[str, tuple[Any, str]]:
    """The ``.msg`` and ``.idl`` definitions under `directory`, each with the file it came from."""
    if not directory.is_dir():
        raise RfcError(f"message directory '{directory}' does not exist")
    files = sorted([*directory.rglob("*.msg"), *directory.rglob("*.idl")])
    if not files:
        raise RfcError(
            f"message directory '{directory}' holds no .msg or .idl files",
            hint="point --msg-path at a folder containing <package>/msg/<Name>.msg",
        )
    definitions: dict[str, tuple[Any, str]] = {}
    for path in files:
        package = path.parent.parent.name if path.parent.name == "msg" else path.parent.name
        try:
            if path.suffix == ".idl":
                parsed = get_types_from_idl(path.read_text())
            else:
                parsed = get_types_from_msg(path.read_text(), f"{package}/msg/{path.stem}")
        except TypesysError as exc:
            raise RfcError(f"{path}: not a valid message definition: {exc}") from None
        definitions.update({name: (fields, str(path)) for name, fields in parsed.items()})
    return definitions


@dataclass(frozen=True)
class _Bag:
    """An open bag: its message connections, their definitions, and what is not a message.

    Attributes:
        reader: The rosbags reader (ROS 1 or ROS 2).
        connections: The connections that carry messages.
        definitions: The message definitions embedded in the bag.
        skipped: ``topic (type)`` of each connection whose schema is not a message (a
            service or an action), left out.
    """

    reader: Any
    connections: tuple[Connection, ...]
    definitions: dict[str, Any]
    skipped: tuple[str, ...]


@contextmanager
def _open_bag(path: Path) -> Iterator[_Bag]:
    """Open a bag, leaving out the connections whose schemas are services or actions."""
    if not path.exists():
        raise RfcError(f"bag '{path}' does not exist")
    try:
        reader = Rosbag1Reader(path) if path.suffix == ".bag" else Rosbag2Reader(path)
        with reader:
            connections, definitions, skipped = [], {}, []
            for connection in reader.connections:
                try:
                    definitions.update(_embedded_definitions(connection))
                except TypesysError as exc:
                    if not _is_service_or_action(connection):
                        raise RfcError(
                            f"cannot read the definition of {connection.msgtype} in bag "
                            f"'{path}': {exc}"
                        ) from None
                    skipped.append(f"{connection.topic} ({connection.msgtype})")
                    continue
                connections.append(connection)
            yield _Bag(reader, tuple(connections), definitions, tuple(skipped))
    except (Rosbag1ReaderError, Rosbag2ReaderError) as exc:
        raise RfcError(f"cannot read bag '{path}': {exc}") from None


def _embedded_definitions(connection: Connection) -> dict[str, Any]:
    """The definitions a connection carries (as rosbags' own reader parses them)."""
    definition = connection.msgdef
    if definition.format == MessageDefinitionFormat.NONE or not definition.data.strip():
        return {}
    if definition.format == MessageDefinitionFormat.MSG:
        return dict(get_types_from_msg(definition.data, connection.msgtype))
    separator = "=" * 80 + "\n"
    if not definition.data.startswith(f"{separator}IDL: "):
        return dict(get_types_from_idl(definition.data))
    found: dict[str, Any] = {}
    for part in definition.data.split(separator)[1:]:
        found.update(get_types_from_idl(part.split("\n", 1)[1]))
    return found


def _is_service_or_action(connection: Connection) -> bool:
    kind = connection.msgtype.split("/")[1:2]
    return kind in (["srv"], ["action"]) or "\n---" in connection.msgdef.data


def skipped_topics(path: str | Path) -> tuple[str, ...]:
    """The bag's topics left out because their schemas are services or actions, not messages.

    Raises:
        RfcError: The bag is missing or unreadable.
    """
    with _open_bag(Path(path)) as bag:
        return bag.skipped


def _definitions_in_bag(bag: Path, store: Typestore) -> dict[str, tuple[Any, str]]:
    with _open_bag(bag) as opened:
        definitions = opened.definitions
    return {
        name: (fields, str(bag))
        for name, fields in definitions.items()
        if name not in store.fielddefs
    }


@cache
def message_types(
    middleware: Middleware | str = Middleware.ROS2,
    distro: str | None = None,
    msg_paths: tuple[str, ...] = (),
    bags: tuple[str, ...] = (),
) -> MessageTypes:
    """Return the shared `MessageTypes` for these sources (built once per process)."""
    return MessageTypes(middleware, distro, msg_paths, bags)


@dataclass(frozen=True)
class BagMessage:
    """One message of a bag: where it was published, when, and its serialized bytes."""

    topic: str
    type_name: str
    timestamp_ns: int
    data: bytes


def read_bag(
    path: str | Path, types: MessageTypes, topics: Iterable[str] = ()
) -> Iterator[BagMessage]:
    """Yield the messages of a ROS 1 or ROS 2 bag in time order, optionally of some topics only.

    Topics whose schemas are services or actions are left out (`skipped_topics` names them).

    Raises:
        RfcError: The bag is missing or unreadable, or a topic asked for is not in it.
    """
    wanted = set(topics)
    with _open_bag(Path(path)) as bag:
        present = {c.topic for c in bag.connections}
        if missing := sorted(wanted - present):
            raise RfcError(
                f"bag '{path}' has no topic '{missing[0]}'",
                hint=did_you_mean(missing[0], present) or _topics_hint(present),
            )
        connections = [c for c in bag.connections if not wanted or c.topic in wanted]
        try:
            for connection, timestamp, raw in bag.reader.messages(connections=connections):
                yield BagMessage(connection.topic, connection.msgtype, timestamp, bytes(raw))
        except (Rosbag1ReaderError, Rosbag2ReaderError) as exc:
            raise RfcError(f"cannot read bag '{path}': {exc}") from None


def _topics_hint(present: Iterable[str]) -> str:
    names = sorted(present)
    return f"its topics are {', '.join(names)}" if names else "it holds no message topics"


def bag_topics(path: str | Path, types: MessageTypes, *, counts: bool = False) -> dict[str, Any]:
    """Return the topics of a bag with their canonical message types (or message counts).

    Raises:
        RfcError: The bag is missing or unreadable.
    """
    with _open_bag(Path(path)) as bag:
        found: dict[str, Any] = {}
        for connection in bag.connections:
            if counts:
                found[connection.topic] = found.get(connection.topic, 0) + connection.msgcount
            else:
                found[connection.topic] = connection.msgtype
        return found


#: Bag formats rfc writes, by the suffix of the path asked for.
BAG_SUFFIXES = {".bag": Middleware.ROS1, ".mcap": Middleware.ROS2, ".db3": Middleware.ROS2}


def check_bag_path(path: str | Path, middleware: Middleware) -> Middleware:
    """Check that a bag of `middleware` messages can be written at `path`.

    Raises:
        RfcError: An unknown suffix, one of the other middleware, a directory, or a missing
            parent directory.
    """
    target = Path(path)
    chosen = BAG_SUFFIXES.get(target.suffix)
    if chosen is None:
        raise RfcError(
            f"cannot tell the bag format of '{target}'",
            hint="end it in .bag (ROS 1), .mcap or .db3 (ROS 2)",
        )
    if chosen is not middleware:
        raise RfcError(
            f"'{target}' would be a {chosen.label} bag, but the messages are {middleware.label}",
            hint="end it in .bag" if middleware is Middleware.ROS1 else "end it in .mcap or .db3",
        )
    if target.is_dir():
        raise RfcError(f"'{target}' is a directory; name a bag file")
    if not target.parent.is_dir():
        raise RfcError(f"the directory of '{target}' does not exist")
    return chosen


def write_bag(
    path: str | Path,
    types: MessageTypes,
    topics: Mapping[str, str],
    messages: Iterable[tuple[str, int, bytes]],
) -> None:
    """Write serialized messages to a new bag with rosbags' writers, all at once or not at all.

    The path's suffix chooses the format: ``.bag`` a ROS 1 bag, ``.mcap`` or ``.db3`` a
    single-file ROS 2 bag of that storage. The bag is written beside `path` and renamed into
    place when complete; an existing file at `path` is replaced.

    Args:
        path: Where the bag goes.
        types: The definitions of the messages (and the middleware they are serialized for).
        topics: Every topic to create, with its canonical type (even if no message comes).
        messages: (topic, time stamp in ns, serialized bytes) in time order.

    Raises:
        RfcError: An unknown suffix, a middleware the format does not carry, or a write error.
    """
    target = Path(path)
    middleware = check_bag_path(target, types.middleware)
    with tempfile.TemporaryDirectory(prefix=f".{target.name}.", dir=target.parent) as scratch:
        try:
            writer: Rosbag1Writer | Rosbag2Writer
            if middleware is Middleware.ROS1:
                writer = Rosbag1Writer(Path(scratch) / f"out{target.suffix}")
            else:
                mcap = target.suffix == ".mcap"
                storage = StoragePlugin.MCAP if mcap else StoragePlugin.SQLITE3
                writer = Rosbag2Writer(Path(scratch) / "out", version=9, storage_plugin=storage)
            with writer:
                connections = {
                    topic: writer.add_connection(topic, msgtype, typestore=types._store)
                    for topic, msgtype in topics.items()
                }
                for topic, stamp, data in messages:
                    writer.write(connections[topic], stamp, data)
            (result,) = Path(scratch).rglob(f"*{target.suffix}")  # a ROS 2 bag's is in out/
            result.replace(target)
        except (OSError, WriterError, Rosbag1WriterError) as exc:
            raise RfcError(f"cannot write bag '{target}': {exc}") from None
