"""The BW4T world in simulated time: zones, doors, blocks, the drop zone and its sequence.

After BW4T 3's server model (``MapLoader``, ``Zone``, ``Room``, ``DropZone``, ``Door``,
``ZoneLocator``, ``PathPlanner``): rooms are entered only through a door and hold one robot at
a time; robots navigate from zone centre to zone centre along the shortest path of the zone
graph; a block dropped in the drop zone counts if it has the colour next in the sequence and is
gone either way; one dropped in a room lands on a free spot; one dropped elsewhere is lost.
Object ids come from one counter, in BW4T's creation order (corridors, rooms with their doors,
blockades, charging zones, blocks, robots). Random parts (random blocks and sequence colours,
block places) use ``java.util.Random`` with BW4T's seeding, so a seeded map matches BW4T's.
Robots and their motion are in ``robot.py``; the EIS side is in ``environment.py``.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass, field

from goalagent.eis.envs.bw4t.geometry import BLOCK_SIZE, Point, Rect, find_free_place
from goalagent.eis.envs.bw4t.mapfile import COLOURS, DROP_ZONE, MAX_BLOCKS_PER_ROOM, MapSpec
from goalagent.eis.envs.bw4t.robot import Robot
from goalagent.eis.envs.javarandom import JavaRandom, java_hashmap_order
from goalagent.eis.exceptions import ManagementException

DOOR_WIDTH = 4.0
DOOR_THICKNESS = 1.0


@dataclass(eq=False)
class Zone:
    """A zone: ``kind`` is ROOM (the drop zone included), CORRIDOR, CHARGINGZONE or BLOCKADE."""

    id: int
    name: str
    kind: str
    rect: Rect
    neighbours: list[Zone] = field(default_factory=list)  # as the map declares them
    linked: list[Zone] = field(default_factory=list)  # the path graph's edges, both ways

    @property
    def centre(self) -> Point:
        return self.rect.centre

    @property
    def is_room(self) -> bool:
        """Rooms (and blockades, rooms without doors) are entered through doors, one robot in."""
        return self.kind in ("ROOM", "BLOCKADE")


@dataclass(eq=False)
class Door:
    """A door into ``room``; a robot must stand in it to move into a room."""

    id: int
    rect: Rect
    room: Zone
    orientation: str


@dataclass(eq=False)
class Block:
    """A coloured block; ``holder`` is the robot carrying it, ``placed`` False once gone."""

    id: int
    colour: str
    x: float
    y: float
    holder: Robot | None = None
    placed: bool = True

    @property
    def rect(self) -> Rect:
        return Rect.centred(self.x, self.y, BLOCK_SIZE, BLOCK_SIZE)


class World:
    """A loaded map: zones, doors, blocks, robots, and the drop zone's sequence."""

    def __init__(self, spec: MapSpec, seed: int, bots: int, humans: int = 0,
                 collision: bool = False) -> None:
        self.spec = spec
        self.seed = spec.seed if spec.seed is not None else seed
        self.one_bot_per_corridor = spec.one_bot_per_corridor_zone
        self.collision = collision
        self._next_id = 0
        self.zones: list[Zone] = []
        self.doors: list[Door] = []
        self._build_zones()
        self.by_name = {zone.name: zone for zone in self.zones}
        self.zones_overlap = any(a.rect.intersects(b.rect) for i, a in enumerate(self.zones)
                                 for b in self.zones[i + 1:])
        self.drop_zone = self.by_name[DROP_ZONE]
        self.sequence = list(spec.sequence)
        self.sequence_index = 0
        self.blocks: list[Block] = []
        self._make_blocks()
        self.robots: list[Robot] = []
        self._spawn(bots, humans)

    def new_id(self) -> int:
        """The next object id (one counter for everything, as in BW4T)."""
        self._next_id += 1
        return self._next_id - 1

    # ---- building the world -----------------------------------------------------------

    def _build_zones(self) -> None:
        specs = self.spec.zones
        order = [z for z in specs if z.kind == "CORRIDOR"] + [z for z in specs if z.kind == "ROOM"]
        order += [z for z in specs if z.kind == "BLOCKADE"]
        order += [z for z in specs if z.kind == "CHARGINGZONE"]
        for zspec in order:
            zone = Zone(self.new_id(), zspec.name, zspec.kind,
                        Rect.centred(zspec.x, zspec.y, zspec.width, zspec.height))
            self.zones.append(zone)
            if zspec.kind == "ROOM":
                for door in zspec.doors:
                    horizontal = door.orientation == "HORIZONTAL"
                    width = DOOR_WIDTH if horizontal else DOOR_THICKNESS
                    height = DOOR_THICKNESS if horizontal else DOOR_WIDTH
                    rect = Rect.centred(door.x, door.y, width, height)
                    self.doors.append(Door(self.new_id(), rect, zone, door.orientation))
        by_name = {zone.name: zone for zone in self.zones}
        for zspec in specs:
            zone = by_name[zspec.name]
            for name in zspec.neighbours:
                neighbour = by_name[name]
                zone.neighbours.append(neighbour)
                for a, b in ((zone, neighbour), (neighbour, zone)):  # an undirected graph
                    if b not in a.linked:
                        a.linked.append(b)

    def _random_colours(self, count: int) -> list[str]:
        """``count`` random block colours, from a fresh ``Random(seed)`` as BW4T draws them."""
        available = [colour for colour in COLOURS if colour != "DARK_GRAY"]
        random = JavaRandom(self.seed)
        return [available[random.next_int_below(len(available))] for _ in range(count)]

    def _make_blocks(self) -> None:
        """The map's blocks plus the random extra ones, placed as ``MapLoader`` places them."""
        rooms = [z for z in self.spec.zones if z.kind == "ROOM" and z.name != DROP_ZONE]
        colours = {zone.name: list(zone.blocks) for zone in rooms}
        extra_sequence = self._random_colours(self.spec.random_sequence)
        self.sequence += extra_sequence
        extra = extra_sequence + self._random_colours(self.spec.random_blocks)
        order = java_hashmap_order([zone.name for zone in rooms])
        if extra and sum(MAX_BLOCKS_PER_ROOM - len(c) for c in colours.values()) < len(extra):
            raise ManagementException(
                f"bw4t map '{self.spec.name}': no room left for {len(extra)} random blocks "
                f"(at most {MAX_BLOCKS_PER_ROOM} per room)"
            )
        random = JavaRandom(self.seed)
        for colour in extra:
            while True:
                room = order[random.next_int_below(len(order))]
                if len(colours[room]) < MAX_BLOCKS_PER_ROOM:
                    colours[room].append(colour)
                    break
        for name in order:
            rect = self.by_name[name].rect
            placing = JavaRandom(self.seed)
            taken: list[Rect] = []
            for colour in colours[name]:
                spot = find_free_place(rect, taken, placing)
                taken.append(spot)
                self.blocks.append(Block(self.new_id(), colour, *spot.centre))

    def _spawn(self, bots: int, humans: int) -> None:
        spawns = self.spec.spawns
        if bots + humans > len(spawns):
            raise ManagementException(
                f"bw4t map '{self.spec.name}' has {len(spawns)} robot start positions, "
                f"{bots + humans} robots asked for (agentcount + humancount)"
            )
        names = [(f"Bot_{i}", "bot") for i in range(1, bots + 1)]
        names += [(f"Human_{i}", "human") for i in range(1, humans + 1)]
        for (name, kind), (x, y) in zip(names, spawns, strict=False):
            self.robots.append(Robot(self, self.new_id(), name, kind, x, y))

    # ---- where things are --------------------------------------------------------------

    def zone_at(self, x: float, y: float) -> Zone | None:
        """The first zone containing the point (``ZoneLocator.getZoneAt``)."""
        for zone in self.zones:
            if zone.rect.contains(x, y):
                return zone
        return None

    def zones_at(self, x: float, y: float) -> list[Zone]:
        return [zone for zone in self.zones if zone.rect.contains(x, y)]

    def nearest_zone(self, x: float, y: float) -> Zone | None:
        """The zone at the point, else the nearest one that is not a room."""
        zone = self.zone_at(x, y)
        if zone is not None:
            return zone
        open_zones = [z for z in self.zones if not z.is_room]
        return min(open_zones, key=lambda z: math.dist(z.centre, (x, y)), default=None)

    def room_at(self, x: float, y: float) -> Zone | None:
        for zone in self.zones:
            if zone.is_room and zone.rect.contains(x, y):
                return zone
        return None

    def door_at(self, x: float, y: float) -> Door | None:
        for door in self.doors:
            if door.rect.contains(x, y):
                return door
        return None

    def occupier(self, zone: Zone) -> Robot | None:
        """The first robot standing in ``zone`` (``Zone.getOccupier``)."""
        for robot in self.robots:
            if zone.rect.contains(robot.x, robot.y):
                return robot
        return None

    def blocks_in(self, rect: Rect) -> list[Block]:
        """Blocks lying in the world (not held, not delivered) inside ``rect``."""
        return [b for b in self.blocks if b.placed and b.holder is None and rect.contains(b.x, b.y)]

    def find_path(self, start: Zone, end: Zone) -> list[Point]:
        """Zone centres from ``start`` to ``end`` on the shortest zone path; [] if unreachable."""
        distance = {start.id: 0.0}
        previous: dict[int, Zone] = {}
        queue: list[tuple[float, int, Zone]] = [(0.0, 0, start)]
        counter = 1
        while queue:
            dist, _, zone = heapq.heappop(queue)
            if zone is end:
                break
            if dist > distance[zone.id]:
                continue
            for neighbour in zone.linked:
                candidate = dist + math.dist(zone.centre, neighbour.centre)
                if candidate < distance.get(neighbour.id, math.inf):
                    distance[neighbour.id] = candidate
                    previous[neighbour.id] = zone
                    heapq.heappush(queue, (candidate, counter, neighbour))
                    counter += 1
        if end.id not in distance:
            return []
        path = [end]
        while path[-1] is not start:
            path.append(previous[path[-1].id])
        return [zone.centre for zone in reversed(path)]

    # ---- time and deliveries -----------------------------------------------------------

    def tick(self) -> None:
        """One step of simulated time: every robot moves (``AbstractRobot.move``), in order."""
        for robot in self.robots:
            robot.move()

    def deliver(self, block: Block, robot: Robot) -> bool:
        """``DropZone.dropped``: True (block gone) when the robot touches the drop zone."""
        if not self.drop_zone.rect.intersects(robot.rect):
            return False
        if self.sequence_index < len(self.sequence):
            if self.sequence[self.sequence_index] == block.colour:
                self.sequence_index += 1
        block.placed = False
        return True

    @property
    def sequence_done(self) -> bool:
        return self.sequence_index >= len(self.sequence)
