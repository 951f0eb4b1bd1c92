"""Garbage cans as data: read a can description (YAML) into a ``CanSpec``, with located errors.

A can file names the can, its mechanism, dimensions, lid (and handle or pedal) and paint; the
structure is the JSON Schema ``sim/cans/can.schema.json`` (checked with ``jsonschema``), then
a few rules the schema cannot say (a handle can needs a handle, the lid marker must fit on the
lid, paint must not look like a marker). Every problem is reported as ``file:line:col: what``.

Why YAML: the cans need comments and the errors need positions. TOML's Python parsers
(tomllib, tomlkit) give no positions for values, JSON has no comments, while PyYAML's
composer gives the line and column of every node, so a schema error's path maps to its place.
The shipped cans (the thesis's o1..o5 and two new mechanisms) live in ``sim/cans/``.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Sequence
from functools import cache
from pathlib import Path

import jsonschema
import yaml

from ondisk import read_bounded
from sim.canspec import MARKER_SIZE, CanSpec

CAN_DIR = Path(__file__).parent / "cans"
SCHEMA_PATH = CAN_DIR / "can.schema.json"
MAX_SATURATION = 0.3
"""Paint may be tinted at most this much ((max - min) / max of RGB) ..."""
MIN_BRIGHTNESS = 0.3
"""... and no darker than this, so it is never seen as a marker or as the dark inside."""
PARTS_BY_MECHANISM = {"lift_handle": "handle", "pull_handle": "handle", "pedal": "pedal"}
GEARED = ("lift_handle", "pull_handle", "pedal", "slide_lid")
MAX_CAN_BYTES = 64 * 1024
"""Largest can file read (the shipped ones are under 1 kB)."""
MAX_NESTING = 16
"""Deepest nesting of mappings and lists accepted (a can file is three deep)."""
MAX_NUMBER_CHARS = 32
"""Longest number accepted, in characters (a measurement needs a handful)."""


class CanFileError(ValueError):
    """A can description that cannot be used; the message starts with file:line:col."""


@cache
def _schema_validator() -> jsonschema.protocols.Validator:
    """The schema's validator (read once)."""
    schema = json.loads(SCHEMA_PATH.read_text(encoding="utf-8"))
    cls = jsonschema.validators.validator_for(schema)
    cls.check_schema(schema)
    return cls(schema)


class _BoundedLoader(yaml.SafeLoader):
    """PyYAML's safe loader within a can file's bounds, each refusal a located CanFileError:
    no aliases (a few lines of nested aliases expand to billions of nodes for every later
    walk), nesting at most MAX_NESTING deep (the composer recurses per level), numbers of at
    most MAX_NUMBER_CHARS characters (Python refuses to convert a 5,000-digit integer) that
    are finite (``1.0e+400`` and ``.inf`` are no measurement)."""

    def __init__(self, text: str, source: str) -> None:
        super().__init__(text)
        self.source = source
        self._depth = 0

    def _fail(self, mark: yaml.Mark, message: str) -> CanFileError:
        return CanFileError(f"{self.source}:{mark.line + 1}:{mark.column + 1}: {message}")

    def compose_node(self, parent: yaml.Node | None, index: object) -> yaml.Node | None:
        event = self.peek_event()
        if isinstance(event, yaml.AliasEvent):
            raise self._fail(event.start_mark, f"an alias (*{event.anchor}): YAML aliases are "
                             "not accepted in a can file; write the value out")
        if self._depth >= MAX_NESTING:
            raise self._fail(event.start_mark, f"nested more than {MAX_NESTING} deep")
        self._depth += 1
        try:
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1

    def construct_number(self, node: yaml.ScalarNode) -> int | float:
        """An int or float scalar, bounded in length and finite."""
        if len(node.value) > MAX_NUMBER_CHARS:
            raise self._fail(node.start_mark, f"a number of {len(node.value)} characters (at "
                             f"most {MAX_NUMBER_CHARS} are accepted)")
        if node.tag.endswith(":int"):
            return self.construct_yaml_int(node)
        value = self.construct_yaml_float(node)
        if not math.isfinite(value):
            raise self._fail(node.start_mark, f"{node.value} is not a finite number")
        return value


_BoundedLoader.add_constructor("tag:yaml.org,2002:int", _BoundedLoader.construct_number)
_BoundedLoader.add_constructor("tag:yaml.org,2002:float", _BoundedLoader.construct_number)


class _Located:
    """A parsed YAML document with the position of every node, to place errors."""

    def __init__(self, text: str, source: str) -> None:
        self.source = source
        loader: _BoundedLoader | None = None
        try:
            loader = _BoundedLoader(text, source)  # its reader refuses control characters
            self.root = loader.get_single_node()
            self.data = None if self.root is None else loader.construct_document(self.root)
        except yaml.reader.ReaderError as exc:
            before = text[:exc.position]
            where = self._at(before.count("\n"), len(before) - before.rfind("\n") - 1)
            raise CanFileError(f"{where}: not valid YAML: the character U+{exc.character:04X} "
                               "is not allowed") from None
        except yaml.MarkedYAMLError as exc:
            mark = exc.problem_mark or exc.context_mark
            where = self._at(mark.line, mark.column) if mark else f"{source}:1:1"
            problem = " ".join(str(p) for p in (exc.context, exc.problem) if p)
            raise CanFileError(f"{where}: not valid YAML: {problem}") from None
        except yaml.YAMLError as exc:
            raise CanFileError(f"{source}:1:1: not valid YAML: {exc}") from None
        finally:
            if loader is not None:
                loader.dispose()
        if self.root is not None:
            self._check_duplicates(self.root)

    def _at(self, line: int, column: int) -> str:
        return f"{self.source}:{line + 1}:{column + 1}"

    def _check_duplicates(self, node: yaml.Node) -> None:
        """YAML would keep the last of two equal keys silently; a can file must not."""
        if isinstance(node, yaml.MappingNode):
            seen: set[object] = set()
            for key, value in node.value:
                if key.value in seen:
                    raise CanFileError(f"{self._at(key.start_mark.line, key.start_mark.column)}:"
                                       f" key {key.value!r} appears twice")
                seen.add(key.value)
                self._check_duplicates(value)
        elif isinstance(node, yaml.SequenceNode):
            for item in node.value:
                self._check_duplicates(item)

    def where(self, path: Sequence[object], key: str | None = None) -> str:
        """file:line:col of the value at ``path`` (or of ``key`` inside it)."""
        node = self.root
        for step in path:
            node = self._child(node, step, want_key=False) or node
        if key is not None:
            node = self._child(node, key, want_key=True) or node
        if node is None:
            return f"{self.source}:1:1"
        return self._at(node.start_mark.line, node.start_mark.column)

    @staticmethod
    def _child(node: yaml.Node | None, step: object, want_key: bool) -> yaml.Node | None:
        if isinstance(node, yaml.MappingNode):
            for key, value in node.value:
                if key.value == step:
                    return key if want_key else value
        if isinstance(node, yaml.SequenceNode) and isinstance(step, int) and (
                0 <= step < len(node.value)):
            return node.value[step]
        return None

    def fail(self, message: str, path: Sequence[object] = (), key: str | None = None) -> None:
        raise CanFileError(f"{self.where(path, key)}: {message}")


def _schema_errors(doc: _Located) -> None:
    """Raise the first schema violation (in document order) at its place."""
    errors = list(_schema_validator().iter_errors(doc.data))
    if not errors:
        return
    placed = []
    for error in errors:
        path = list(error.absolute_path)
        key = None
        if error.validator == "additionalProperties" and isinstance(error.instance, dict):
            allowed = set(error.schema.get("properties", {}))
            extra = sorted(k for k in error.instance if k not in allowed)
            key = extra[0] if extra else None
            message = f"unknown key {key!r}; allowed here: {', '.join(sorted(allowed))}"
        elif error.validator == "required":
            message = error.message.replace("is a required property", "is missing")
        else:
            name = ".".join(str(p) for p in path) or "the file"
            message = f"{name}: {_shortened(error.message)}"
        placed.append((doc.where(path, key), message))
    where, message = min(placed, key=lambda item: _position(item[0]))
    raise CanFileError(f"{where}: {message}")


def _shortened(message: str, keep: int = 200) -> str:
    """A schema message cut to ``keep`` characters (it quotes the value: a name may be 60 kB)."""
    return message if len(message) <= keep else f"{message[:keep]}... ({len(message)} characters)"


def _position(where: str) -> tuple[int, int]:
    """(line, col) of a file:line:col string, to report the earliest problem first."""
    _, line, col = where.rsplit(":", 2)
    return int(line), int(col)


def parse_can(text: str, source: str = "<can>") -> CanSpec:
    """A CanSpec from the text of a can file (``source`` names it in errors)."""
    doc = _Located(text, source)
    if not isinstance(doc.data, dict):
        raise CanFileError(f"{source}:1:1: a can file is a mapping of keys (name, mechanism, "
                           "dimensions, lid, ...)")
    _schema_errors(doc)
    data = doc.data
    mechanism = data["mechanism"]
    kind = mechanism["type"]
    if kind in GEARED and "gear" not in mechanism:
        doc.fail(f"a {kind} mechanism needs a gear (lid angle per metre of travel)",
                 ["mechanism"])
    if kind not in GEARED and "gear" in mechanism:
        doc.fail(f"a {kind} mechanism has no gear", ["mechanism"], "gear")
    if (kind == "slide_lid") != ("direction" in mechanism):
        doc.fail("a slide_lid mechanism needs a direction (left or right), no other has one",
                 ["mechanism"], "direction" if "direction" in mechanism else None)
    for section in ("handle", "pedal"):
        if section in data and PARTS_BY_MECHANISM.get(kind) != section:
            doc.fail(f"a {kind} can has no {section}", [], section)
    lid, dims = data["lid"], data["dimensions"]
    if kind == "slide_lid":
        if "marker_z" in lid:
            doc.fail("a sliding lid carries its marker on the tab at its front edge",
                     ["lid"], "marker_z")
        marker_z = lid["height"] - MARKER_SIZE["lid"][1] / 2
    else:
        if "marker_z" not in lid:
            doc.fail("lid.marker_z is missing (the marker's centre above the lid's underside)",
                     ["lid"])
        marker_z = lid["marker_z"]
        half = MARKER_SIZE["lid"][1] / 2
        if not half <= marker_z <= lid["height"] - half:
            doc.fail(f"lid.marker_z {marker_z} puts the 2 cm marker off a "
                     f"{lid['height']} m lid", ["lid", "marker_z"])
    handle = data.get("handle", {})
    drop = handle.get("drop", 0.13)
    if "handle" in data and drop > 0.8 * dims["height"] - 0.04:
        doc.fail(f"handle.drop {drop} puts the handle over the body marker (at most "
                 f"{0.8 * dims['height'] - 0.04:.3f} for this height)", ["handle", "drop"])
    give = data.get("give", {})
    if "handle" in give and "handle" not in data and PARTS_BY_MECHANISM.get(kind) != "handle":
        doc.fail(f"a {kind} can has no handle to give play to", ["give"], "handle")
    colours = data.get("colours", {})
    for part, rgb in colours.items():
        low, high = min(rgb), max(rgb)
        if low < MIN_BRIGHTNESS or (high - low) / high > MAX_SATURATION:
            doc.fail(f"the {part} paint {rgb} is too dark or too colourful: the camera would "
                     "take it for a marker or for the dark inside", ["colours", part])
    optional: dict[str, object] = {"gear": float(mechanism.get("gear", 0.0)),
                                   "handle_drop": drop}
    if "direction" in mechanism:
        optional["slide"] = mechanism["direction"]
    if "height" in data.get("pedal", {}):
        optional["pedal_z"] = data["pedal"]["height"]
    if "handle" in give:
        optional["handle_play"] = tuple(give["handle"]["axes"])
        optional["play_travel"] = float(give["handle"]["travel"])
    if "can" in give:
        optional["can_slide"] = float(give["can"]["slide"])
    for part in ("body", "lid"):
        if part in colours:
            optional[f"{part}_colour"] = tuple(float(x) for x in colours[part])
    return CanSpec(name=data["name"], mechanism=kind, width=dims["width"], depth=dims["depth"],
                   height=dims["height"], lid_height=lid["height"], lid_marker_z=marker_z,
                   source=source, **optional)  # type: ignore[arg-type]


def load_can(path: str | os.PathLike[str]) -> CanSpec:
    """Read the can described in the file at ``path``."""
    source = Path(path)
    try:
        data = read_bounded(source, MAX_CAN_BYTES)
    except (OSError, ValueError) as exc:  # ValueError: a NUL byte in the path
        reason = getattr(exc, "strerror", None) or exc
        raise CanFileError(f"{source}:1:1: cannot read the can file: {reason}") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        before = data[:exc.start].decode("utf-8", errors="replace")
        line, col = before.count("\n") + 1, len(before) - before.rfind("\n")
        raise CanFileError(f"{source}:{line}:{col}: not UTF-8 text (byte "
                           f"0x{data[exc.start]:02x})") from None
    return parse_can(text, str(source))


def shipped_cans() -> dict[str, Path]:
    """The can files shipped with goalagent, by name (the file's stem)."""
    return {path.stem: path for path in sorted(CAN_DIR.glob("*.yaml"))}


def shipped_can_path(name: str) -> Path:
    """The file of the shipped can called ``name``."""
    return CAN_DIR / f"{name}.yaml"


def find_can(name_or_path: str | os.PathLike[str]) -> CanSpec:
    """A shipped can by name (o1 .. o5, slide, pedal) or a can file by path."""
    text = str(name_or_path)
    shipped = shipped_cans()
    if text in shipped:
        return load_can(shipped[text])
    if text.endswith((".yaml", ".yml")) or os.sep in text or Path(text).exists():
        return load_can(text)
    raise CanFileError(f"unknown can {text!r}: name a shipped can ({', '.join(shipped)}) or "
                       "give the path of a can file (.yaml)")
