"""BW4T map files: the XML that BW4T 3 (and BW4T 2) read with JAXB into ``NewMap``.

```xml
<newMap>
  <area><x>50.0</x><y>40.0</y></area>                  map size
  <entities><name>Bot1</name><position><x>5.0</x><y>35.0</y></position>
            <type>NORMAL</type></entities>           one spawn point per robot, in order
  <oneBotPerCorridorZone>false</oneBotPerCorridorZone>
  <randomBlocks>0</randomBlocks>                       extra blocks of random colours
  <randomSequence>0</randomSequence>                   extra random colours in the sequence
  <seed>3</seed>                                       optional: seeds the random parts
  <sequence>RED</sequence> ...                         the colours to deliver, in order
  <zones>
    <blocks>RED</blocks> ...                           blocks in this room
    <boundingbox><height>10.0</height><width>10.0</width><x>15.0</x><y>15.0</y></boundingbox>
    <doors><orientation>HORIZONTAL</orientation><position><x>15.0</x><y>10.0</y></position></doors>
    <name>RoomA1</name>
    <neighbours>FrontRoomA1</neighbours> ...
    <type>ROOM</type>                                  ROOM | CORRIDOR | CHARGINGZONE | BLOCKADE
  </zones> ...
</newMap>
```

Bounding boxes are given by their centre. The drop zone is the ROOM called ``DropZone``.
Elements JAXB would ignore (``renderOptions``, unknown ones) are ignored here too. Python's
standard ``xml.etree.ElementTree`` reads the file; this module checks what BW4T would choke on
and says so with the map's name and the zone concerned.
"""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from goalagent.eis.exceptions import ManagementException

COLOURS = ("RED", "ORANGE", "YELLOW", "GREEN", "BLUE", "PINK", "WHITE", "DARK_GRAY")
ZONE_TYPES = ("ROOM", "CORRIDOR", "CHARGINGZONE", "BLOCKADE")
DROP_ZONE = "DropZone"
MAPS_DIR = Path(__file__).with_name("maps")
MAX_BLOCKS_PER_ROOM = 10


def colour_name(colour: str) -> str:
    """The name BW4T's percepts use for a colour: ``RED`` -> ``Red``, ``DARK_GRAY`` ->
    ``Dark_gray``."""
    return colour[0] + colour[1:].lower()


@dataclass(frozen=True)
class DoorSpec:
    """A door: its centre and whether it lies along x (HORIZONTAL) or y (VERTICAL)."""

    x: float
    y: float
    orientation: str


@dataclass(frozen=True)
class ZoneSpec:
    """One zone of the map as written in the file."""

    name: str
    kind: str
    x: float
    y: float
    width: float
    height: float
    neighbours: tuple[str, ...]
    doors: tuple[DoorSpec, ...]
    blocks: tuple[str, ...]


@dataclass(frozen=True)
class MapSpec:
    """A whole map file."""

    name: str
    width: float
    height: float
    zones: tuple[ZoneSpec, ...]
    sequence: tuple[str, ...]
    spawns: tuple[tuple[float, float], ...]
    one_bot_per_corridor_zone: bool
    random_blocks: int
    random_sequence: int
    seed: int | None


class _Reader:
    """Reads elements of one map file, turning bad values into located messages."""

    def __init__(self, name: str) -> None:
        self.name = name

    def fail(self, message: str) -> ManagementException:
        return ManagementException(f"bw4t map '{self.name}': {message}")

    def text(self, element: ElementTree.Element, tag: str, where: str,
             default: str | None = None) -> str:
        child = element.find(tag)
        if child is None or child.text is None or not child.text.strip():
            if default is not None:
                return default
            raise self.fail(f"{where} has no <{tag}>")
        return child.text.strip()

    def number(self, element: ElementTree.Element, tag: str, where: str,
               default: str | None = None) -> float:
        text = self.text(element, tag, where, default)
        try:
            return float(text)
        except ValueError:
            raise self.fail(f"{where}: <{tag}> must be a number, got {text!r}") from None

    def whole(self, element: ElementTree.Element, tag: str, where: str, default: str) -> int:
        value = self.number(element, tag, where, default)
        if not value.is_integer() or value < 0:
            raise self.fail(f"{where}: <{tag}> must be a whole number >= 0, got {value}")
        return int(value)

    def point(self, element: ElementTree.Element | None, where: str) -> tuple[float, float]:
        if element is None:
            raise self.fail(f"{where} has no position")
        return self.number(element, "x", where), self.number(element, "y", where)

    def colour(self, text: str | None, where: str) -> str:
        colour = (text or "").strip().upper()
        if colour not in COLOURS:
            raise self.fail(f"{where}: unknown colour {text!r} (colours: {', '.join(COLOURS)})")
        return colour

    def zone(self, element: ElementTree.Element) -> ZoneSpec:
        name = self.text(element, "name", "a zone")
        where = f"zone '{name}'"
        kind = self.text(element, "type", where).upper()
        if kind not in ZONE_TYPES:
            raise self.fail(f"{where}: unknown type {kind!r} (types: {', '.join(ZONE_TYPES)})")
        box = element.find("boundingbox")
        if box is None:
            raise self.fail(f"{where} has no <boundingbox>")
        width = self.number(box, "width", where)
        height = self.number(box, "height", where)
        if width <= 1 or height <= 0:
            raise self.fail(f"{where}: the bounding box must be wider than 1 and higher than 0")
        doors = []
        for door in element.findall("doors"):
            orientation = self.text(door, "orientation", f"a door of {where}", "HORIZONTAL")
            if orientation.upper() not in ("HORIZONTAL", "VERTICAL"):
                raise self.fail(f"{where}: door orientation must be HORIZONTAL or VERTICAL")
            x, y = self.point(door.find("position"), f"a door of {where}")
            doors.append(DoorSpec(x, y, orientation.upper()))
        blocks = tuple(self.colour(b.text, where) for b in element.findall("blocks"))
        if len(blocks) > MAX_BLOCKS_PER_ROOM:
            raise self.fail(f"{where} has {len(blocks)} blocks; a room holds at most "
                            f"{MAX_BLOCKS_PER_ROOM}")
        if blocks and kind != "ROOM":
            raise self.fail(f"{where}: only rooms hold blocks, this is a {kind}")
        neighbours = tuple((n.text or "").strip() for n in element.findall("neighbours"))
        return ZoneSpec(name, kind, self.number(box, "x", where), self.number(box, "y", where),
                        width, height, neighbours, tuple(doors), blocks)


def parse_map(text: str, name: str) -> MapSpec:
    """A map from the XML text of a map file; ``name`` is used in messages."""
    reader = _Reader(name)
    try:
        root = ElementTree.fromstring(text)
    except ElementTree.ParseError as error:
        line, column = error.position
        raise reader.fail(f"not readable XML at line {line}, column {column + 1}") from None
    if root.tag != "newMap":
        raise reader.fail(f"the root element must be <newMap>, got <{root.tag}>")
    area = root.find("area")
    if area is None:
        raise reader.fail("no <area>")
    zones = tuple(reader.zone(element) for element in root.findall("zones"))
    names = [zone.name for zone in zones]
    for zone in zones:
        if names.count(zone.name) > 1:
            raise reader.fail(f"two zones are called '{zone.name}'")
        for neighbour in zone.neighbours:
            if neighbour not in names:
                raise reader.fail(f"zone '{zone.name}': neighbour '{neighbour}' is not a zone")
    drop = [zone for zone in zones if zone.name == DROP_ZONE]
    if not drop or drop[0].kind != "ROOM":
        raise reader.fail(f"no ROOM called '{DROP_ZONE}' (the drop zone)")
    flag = reader.text(root, "oneBotPerCorridorZone", "the map", "false").lower()
    if flag not in ("true", "false"):
        raise reader.fail(f"<oneBotPerCorridorZone> must be true or false, got {flag!r}")
    seed = root.find("seed")
    return MapSpec(
        name=name,
        width=reader.number(area, "x", "<area>"),
        height=reader.number(area, "y", "<area>"),
        zones=zones,
        sequence=tuple(reader.colour(s.text, "<sequence>") for s in root.findall("sequence")),
        spawns=tuple(reader.point(e.find("position"), "an <entities> entry")
                     for e in root.findall("entities")),
        one_bot_per_corridor_zone=flag == "true",
        random_blocks=reader.whole(root, "randomBlocks", "the map", "0"),
        random_sequence=reader.whole(root, "randomSequence", "the map", "0"),
        seed=None if seed is None else reader.whole(root, "seed", "the map", "0"),
    )


def shipped_maps() -> list[str]:
    """The names of the maps that come with goalagent."""
    return sorted(path.stem for path in MAPS_DIR.glob("*.map"))


def load_map(spec: str, folders: Sequence[Path] = ()) -> MapSpec:
    """A map by file path (relative: in the working directory, then in ``folders``), or by
    the name of a shipped map (``TwoRooms``, ``TwoRooms.map``; BW4T's standard maps
    ``Random``, ``Banana``, ... also under the path a BW4T setup keeps them at,
    ``environments/maps/Random``, and as ``random``)."""
    path = Path(spec)
    if not path.is_file() and not path.is_absolute():
        path = next((folder / spec for folder in folders if (folder / spec).is_file()), path)
    if not path.is_file():
        name = path.name.removesuffix(".map").casefold()
        # by its name in any case, as BW4T on the Windows file systems of its users found it
        same = [stem for stem in shipped_maps() if stem.casefold() == name]
        shipped = MAPS_DIR / f"{same[0] if same else path.name}.map"
        if not shipped.is_file():
            raise ManagementException(
                f"bw4t: no map file '{spec}' and no shipped map of that name "
                f"(shipped: {', '.join(shipped_maps())})"
            )
        path = shipped
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise ManagementException(f"bw4t: cannot read map file '{path}': {error}") from None
    return parse_map(text, path.stem)
