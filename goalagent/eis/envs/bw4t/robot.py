"""A BW4T robot: navigation in simulated time, collisions, the gripper.

After BW4T 3's ``AbstractRobot`` and ``NavigatingRobot``. A robot is 2x2, moves at most
0.5 x speed (0.5) = 0.25 units per tick towards its current waypoint, and plans waypoints as
zone centres (then the target itself). A step into a room needs the robot to stand in a door
and the room to be empty (else it collides: ``HIT_CLOSED_DOOR``); with
``oneBotPerCorridorZone`` a corridor holds one robot too. With collisions on (the server's
``-collision``), robots also bump into each other. A collided robot stops with state
``collided`` until it is given a new target.

One addition, so agents see ``state(traveling)`` before ``state(arrived)`` as in BW4T (where
moving starts on the server's next tick): a robot given a target waits (``hold``) until its
entity has perceived once.
"""

from __future__ import annotations

import math
from collections import deque
from typing import TYPE_CHECKING

from goalagent.eis.envs.bw4t.geometry import Point, Rect, find_free_place
from goalagent.eis.envs.javarandom import JavaRandom

if TYPE_CHECKING:
    from goalagent.eis.envs.bw4t.world import Block, World, Zone

MAX_MOVE_DISTANCE = 0.5
MIN_MOVE_DISTANCE = 0.001
ARM_DISTANCE = 1.0
ROBOT_SIZE = 2
SPEED_MOD = 0.5


class Unreachable(Exception):
    """The target cannot be reached over the zone graph."""


class Robot:
    """One robot; ``kind`` is ``bot`` or ``human`` (the entity type)."""

    def __init__(self, world: World, robot_id: int, name: str, kind: str,
                 x: float, y: float) -> None:
        self.world = world
        self.id = robot_id
        self.name = name
        self.kind = kind
        self.x, self.y = x, y
        self.size = ROBOT_SIZE
        self.speed_mod = SPEED_MOD
        self.capacity = 1
        self.holding: list[Block] = []  # a stack: the last one is on top
        self.target: Point | None = None
        self.current_move: Point | None = None
        self.planned: deque[Point] = deque()
        self.move_history: Point | None = None
        self.planned_history: list[Point] = []
        self.collided = False
        self.obstacles: list[Robot] = []
        self.unreachable = False
        self.hold = False
        self.has_been_free = False
        self._drop_random = JavaRandom(world.seed * 31 + robot_id)

    # ---- state -------------------------------------------------------------------------

    @property
    def rect(self) -> Rect:
        return Rect.centred(self.x, self.y, self.size, self.size)

    @property
    def state(self) -> str:
        """``collided``, ``arrived`` or ``traveling`` (``NavigatingRobot.getState``)."""
        if self.collided:
            return "collided"
        if self.current_move is None and not self.planned:
            return "arrived"
        return "traveling"

    @property
    def zone(self) -> Zone | None:
        return self.world.zone_at(self.x, self.y)

    def distance_to(self, x: float, y: float) -> float:
        return math.hypot(x - self.x, y - self.y)

    # ---- navigation --------------------------------------------------------------------

    def _fresh_plan(self) -> None:
        self.collided = False
        self.obstacles.clear()
        self.unreachable = False
        self.planned.clear()

    def go_to_object(self, target: Point) -> None:
        """Head for a zone centre or a block: ``NavigatingRobot.setTarget``."""
        path = self._zone_path(target)
        self._fresh_plan()
        self.planned.extend(path)
        self.planned.append(target)
        self.hold = True
        self._next_waypoint()

    def go_to_point(self, target: Point) -> None:
        """Head for a point: ``NavigatingRobot.setTargetLocation`` with its ``planPath``."""
        path = self._zone_path(target)
        start = self.world.nearest_zone(self.x, self.y)
        end = self.world.nearest_zone(*target)
        waypoints: list[Point] = []
        if len(path) == 1:
            waypoints.append(target)
        else:
            starts_in_room = start is not None and start.is_room
            if starts_in_room or (self.x, self.y) != path[0]:
                waypoints.append(path[0])
            pre_last = len(path) - 2
            waypoints.extend(path[1:pre_last])
            if pre_last > 0:
                waypoints.append(path[pre_last])
            last = path[pre_last + 1]
            if ((pre_last == 0 and starts_in_room) or (end is not None and end.is_room)
                    or not _skip_last(path[pre_last], last, target)):
                waypoints.append(last)
            waypoints.append(target)
        self._fresh_plan()
        self.planned.extend(waypoints)
        self.hold = True
        self._next_waypoint()

    def _zone_path(self, target: Point) -> list[Point]:
        start = self.world.nearest_zone(self.x, self.y)
        end = self.world.nearest_zone(*target)
        path = [] if start is None or end is None else self.world.find_path(start, end)
        if not path:
            raise Unreachable(f"({target[0]:g},{target[1]:g}) cannot be reached from "
                              f"({self.x:g},{self.y:g})")
        return path

    def _next_waypoint(self) -> None:
        """``useNextTarget``: aim at the next waypoint, if any."""
        self.current_move = None
        if self.planned:
            self.current_move = self.planned.popleft()
            self.target = self.current_move
            self.collided = False

    def _stop(self) -> None:
        """``stopRobot`` and ``robotStopped``: after a collision the plan is put aside."""
        self.target = None
        if self.collided:
            zone = self.zone
            if zone is not None and self.current_move == zone.centre:
                self.move_history = self.planned.popleft() if self.planned else None
            else:
                self.move_history = self.current_move
            self.planned_history = list(self.planned)
            self.planned.clear()
            return
        self.current_move = None
        self._next_waypoint()

    def navigate_obstacles(self) -> bool:
        """Resume the plan a collision interrupted; False (and unreachable) if there is none.

        BW4T plans a detour on a grid around the robots in the way; here the interrupted
        route is simply tried again (rooms cannot be detoured around anyway).
        """
        route = ([self.move_history] if self.move_history is not None else [])
        route += self.planned_history
        self.obstacles.clear()
        if not route:
            self.unreachable = True
            return False
        self.collided = False
        self.planned.extend(route)
        self.planned_history = []
        self.move_history = None
        self._next_waypoint()
        return True

    # ---- one tick ----------------------------------------------------------------------

    def move(self) -> None:
        """``AbstractRobot.move``: one tick towards the current waypoint."""
        if self.hold or self.target is None or self.obstacles:
            return
        distance = self.distance_to(*self.target)
        if distance < MIN_MOVE_DISTANCE:
            self._stop()
            return
        step = min(distance, MAX_MOVE_DISTANCE * self.speed_mod)
        angle = math.atan2(self.target[1] - self.y, self.target[0] - self.x)
        destination = (self.x + step * math.cos(angle), self.y + step * math.sin(angle))
        other = self._robot_in_the_way(destination)
        if other is not None:
            self.collided = True
            self.obstacles.append(other)
            other.collided = True
            other.obstacles.append(self)
            self._stop()
            return
        if self._blocked(*destination):
            self.collided = True
            self._stop()
            return
        self.x, self.y = destination

    def _robot_in_the_way(self, destination: Point) -> Robot | None:
        """With collisions on: another robot overlapping our box (plus 1) at ``destination``."""
        if not self.world.collision:
            return None
        if not self.has_been_free:
            self.has_been_free = not any(self.rect.intersects(r.rect)
                                         for r in self.world.robots if r is not self)
            return None
        box = Rect.centred(*destination, self.size + 1, self.size + 1)
        for robot in self.world.robots:
            if robot is not self and box.intersects(robot.rect):
                return robot
        return None

    def _blocked(self, x: float, y: float) -> bool:
        """``getMoveType`` is a hit: a wall, a room someone else is in, a full corridor."""
        world = self.world
        start = world.zone_at(self.x, self.y)
        if start is not None and not world.zones_overlap and start.rect.contains(x, y):
            return False  # staying in the zone (the only one there, zones not overlapping)
        door = world.door_at(self.x, self.y)
        for end in world.zones_at(x, y):
            if end is start:
                continue
            if end.is_room:
                occupier = world.occupier(end)
                if door is None or (occupier is not None and occupier is not self):
                    return True
            elif end.kind == "CORRIDOR" and world.one_bot_per_corridor:
                occupier = world.occupier(end)
                if occupier is not None and occupier is not self:
                    return True
        return False

    # ---- the gripper -------------------------------------------------------------------

    def can_pick_up(self, block: Block) -> bool:
        """Within reach (size + arm), lying free, and room in the gripper."""
        return (block.placed and block.holder is None
                and self.distance_to(block.x, block.y) <= self.size + ARM_DISTANCE
                and len(self.holding) < self.capacity)

    def pick_up(self, block: Block) -> None:
        self.holding.append(block)
        block.holder = self

    def drop(self) -> None:
        """Put the top block down: delivered, on a free spot of this room, or lost."""
        block = self.holding.pop()
        block.holder = None
        if self.world.deliver(block, self):
            return
        zone = self.zone
        if zone is None or not zone.is_room:
            block.placed = False  # BW4T drops it out of the world
            return
        taken = [b.rect for b in self.world.blocks_in(zone.rect)]
        block.x, block.y = find_free_place(zone.rect, taken, self._drop_random).centre


def _skip_last(before: Point, last: Point, target: Point) -> bool:
    """``NavigatingRobot.skipLastNode``: go straight to the target from the zone before."""
    if abs(before[0] - last[0]) > 2.0 and abs(before[1] - last[1]) > 2.0:
        return False
    return math.dist(before, target) < math.dist(before, last)
