"""The elevator simulator's building, as a discrete-event simulation in milliseconds.

After the ElevatorSim that GOAL uses (Chris Dailey and Neil McKellar's simulator with W.
Pasman's GOAL controller): floors 10 units apart, cars that travel 10 units in 4.03 s, one door
per floor and car that takes 2 s to open or close, a door sensor that lets the door close 3 s
after the last person passed, people who take 2 s to step in or out. A waiting person presses
the floor's up or down button, boards a car whose arrival light shows their direction and
presses their floor's button inside; people inside get out at their floor first. A car goes
where the controller (the agent) sends it; on arrival it lights the direction the last
``goto`` asked for. Events at the same time run in the order they were scheduled.
"""

from __future__ import annotations

import heapq
from collections.abc import Callable
from dataclasses import dataclass, field

FLOOR_HEIGHT = 10.0
CAR_RATE = 10.0 / 4030.0  # units per millisecond
DOOR_TIME = 2000
SENSOR_CLEAR_TIME = 3000
STEP_TIME = 2000


class EventQueue:
    """Callbacks at simulated times (ms), run in time order, ties in scheduling order."""

    def __init__(self) -> None:
        self.now = 0
        self._heap: list[tuple[int, int, Callable[[], None]]] = []
        self._cancelled: set[int] = set()
        self._counter = 0

    def at(self, time: int, callback: Callable[[], None]) -> int:
        """Schedule ``callback`` at ``time`` (not before now); returns a handle for ``cancel``."""
        self._counter += 1
        heapq.heappush(self._heap, (max(time, self.now), self._counter, callback))
        return self._counter

    def cancel(self, handle: int | None) -> None:
        if handle is not None:
            self._cancelled.add(handle)

    def run_until(self, time: int) -> None:
        """Run every event due up to ``time``; the clock ends at ``time``."""
        while self._heap and self._heap[0][0] <= time:
            when, handle, callback = heapq.heappop(self._heap)
            if handle in self._cancelled:
                self._cancelled.discard(handle)
                continue
            self.now = when
            callback()
        self.now = max(self.now, time)


@dataclass(eq=False)
class Person:
    """A rider: on ``floor`` until carried to ``destination``; ``car`` while inside one."""

    number: int
    floor: int
    destination: int | None = None
    car: Car | None = None
    boarding: bool = False
    arrived: bool = False

    @property
    def up(self) -> bool:
        return self.destination is not None and self.destination > self.floor


@dataclass(eq=False)
class Entrance:
    """The door between one floor and one car, its sensor and its arrival lights."""

    floor: int
    car: Car
    door: str = "closed"  # closed, opening, opened, closing
    percent_closed: float = 100.0
    door_since: int = 0
    door_event: int | None = None
    sensor: str = "clear"  # clear, obstructed, unobstructed
    clear_event: int | None = None
    up: bool = False
    down: bool = False
    leaving: list[Person] = field(default_factory=list)
    watchers: list[Person] = field(default_factory=list)


@dataclass(eq=False)
class Car:
    """A car: docked at ``location`` or moving to ``destination``."""

    number: int
    capacity: int
    height: float = 0.0
    location: int | None = None
    destination: int | None = None
    people: list[Person] = field(default_factory=list)
    requested: list[int] = field(default_factory=list)
    next_up: bool = True
    departed_at: int = 0
    departed_from: float = 0.0
    arrival_event: int | None = None

    @property
    def name(self) -> str:
        return str(self.number)

    @property
    def full(self) -> bool:
        return len(self.people) >= self.capacity


class Building:
    """Floors ``1..floors``, cars ``0..cars-1`` starting undocked at floor 1, and people."""

    def __init__(self, floors: int, cars: int, capacity: int) -> None:
        self.floors = floors
        self.queue = EventQueue()
        self.cars = [Car(number, capacity) for number in range(cars)]
        self.entrances = {(floor, car.number): Entrance(floor, car)
                          for floor in range(1, floors + 1) for car in self.cars}
        self.call_up = [False] * (floors + 1)
        self.call_down = [False] * (floors + 1)
        self.people: list[Person] = []

    # ---- queries ----------------------------------------------------------------------

    def height_of(self, car: Car) -> float:
        """The car's height now (interpolated while it travels)."""
        if car.arrival_event is None or car.destination is None:
            return car.height
        target = (car.destination - 1) * FLOOR_HEIGHT
        travelled = CAR_RATE * (self.queue.now - car.departed_at)
        if target > car.departed_from:
            return min(target, car.departed_from + travelled)
        return max(target, car.departed_from - travelled)

    def floor_of(self, car: Car) -> int | None:
        """The floor the car is at: docked there, or idle at its height (else None)."""
        if car.location is not None:
            return car.location
        if car.destination is None:
            level = car.height / FLOOR_HEIGHT
            if level.is_integer() and 0 <= level < self.floors:
                return int(level) + 1
        return None

    def waiting(self, floor: int) -> list[Person]:
        return [p for p in self.people if p.floor == floor and p.car is None
                and p.destination is not None and not p.boarding and not p.arrived]

    # ---- riders ------------------------------------------------------------------------

    def add_person(self, floor: int) -> Person:
        person = Person(len(self.people) + 1, floor)
        self.people.append(person)
        return person

    def call(self, person: Person, destination: int) -> None:
        """The person wants to go to ``destination`` (``Person.setDestination``)."""
        if destination == person.floor:
            return
        person.destination = destination
        for car in self.cars:
            entrance = self.entrances[(person.floor, car.number)]
            if entrance.door != "closed" and (entrance.up if person.up else entrance.down):
                entrance.watchers.append(person)
        self.try_to_board(person)

    def try_to_board(self, person: Person) -> None:
        """Board a car that is open in the person's direction, or press the call button."""
        if person.car is not None or person.boarding or person.arrived:
            return
        candidates = 0
        for car in self.cars:
            entrance = self.entrances[(person.floor, car.number)]
            if (entrance.door != "closed" and entrance.sensor != "obstructed" and not car.full
                    and not entrance.leaving and person.up == entrance.up):
                self._board(person, entrance)
                return
            if entrance.sensor == "obstructed" or entrance.leaving:
                candidates += 1
        if candidates:
            return
        if person.up:
            self.call_up[person.floor] = True
        else:
            self.call_down[person.floor] = True

    def _board(self, person: Person, entrance: Entrance) -> None:
        person.boarding = True
        for other in self.entrances.values():
            if person in other.watchers:
                other.watchers.remove(person)
        self._obstruct(entrance)

        def step_in() -> None:
            person.boarding = False
            person.car = entrance.car
            entrance.car.people.append(person)
            if person.destination not in entrance.car.requested:
                entrance.car.requested.append(person.destination)
            self._unobstruct(entrance)

        self.queue.at(self.queue.now + STEP_TIME, step_in)

    def _let_out(self, entrance: Entrance) -> None:
        """``chooseSomeoneFromList``: the next person inside steps out when the door is free."""
        if not entrance.leaving:
            return
        if entrance.door == "opening" or entrance.sensor == "obstructed":
            return
        person = entrance.leaving.pop(0)
        self._obstruct(entrance)

        def step_out() -> None:
            entrance.car.people.remove(person)
            person.car = None
            person.floor = entrance.floor
            person.arrived = True
            self._unobstruct(entrance)

        self.queue.at(self.queue.now + STEP_TIME, step_out)

    # ---- doors and sensors --------------------------------------------------------------

    def _door_progress(self, entrance: Entrance) -> float:
        """How far closed the door is now (percent), while it moves."""
        elapsed = (self.queue.now - entrance.door_since) / DOOR_TIME * 100
        if entrance.door == "opening":
            return max(0.0, entrance.percent_closed - elapsed)
        if entrance.door == "closing":
            return min(100.0, entrance.percent_closed + elapsed)
        return entrance.percent_closed

    def _open(self, entrance: Entrance) -> None:
        entrance.percent_closed = self._door_progress(entrance)
        self.queue.cancel(entrance.door_event)
        entrance.door, entrance.door_since = "opening", self.queue.now
        delay = int(entrance.percent_closed / 100 * DOOR_TIME)
        entrance.door_event = self.queue.at(self.queue.now + delay, lambda: self._opened(entrance))

    def _opened(self, entrance: Entrance) -> None:
        entrance.door, entrance.percent_closed, entrance.door_event = "opened", 0.0, None
        floor = entrance.floor
        if entrance.up or entrance.down:
            if entrance.up:
                self.call_up[floor] = False
            else:
                self.call_down[floor] = False
            for person in self.waiting(floor):
                if person.up == entrance.up:
                    if person not in entrance.watchers:
                        entrance.watchers.append(person)
                    self.try_to_board(person)
        if entrance.sensor == "clear":
            self._unobstruct(entrance)

    def _close(self, entrance: Entrance) -> None:
        entrance.door, entrance.door_since = "closing", self.queue.now
        delay = int((100 - entrance.percent_closed) / 100 * DOOR_TIME)
        entrance.door_event = self.queue.at(self.queue.now + delay, lambda: self._closed(entrance))

    def _closed(self, entrance: Entrance) -> None:
        entrance.door, entrance.percent_closed, entrance.door_event = "closed", 100.0, None
        entrance.up = entrance.down = False
        entrance.watchers.clear()
        self._undock(entrance.car)

    def _obstruct(self, entrance: Entrance) -> None:
        if entrance.sensor == "unobstructed":
            self.queue.cancel(entrance.clear_event)
            entrance.clear_event = None
        entrance.sensor = "obstructed"
        if entrance.door == "closing":
            self._open(entrance)

    def _unobstruct(self, entrance: Entrance) -> None:
        entrance.sensor = "unobstructed"
        entrance.clear_event = self.queue.at(self.queue.now + SENSOR_CLEAR_TIME,
                                             lambda: self._cleared(entrance))
        self._let_out(entrance)
        for person in list(entrance.watchers):
            self.try_to_board(person)

    def _cleared(self, entrance: Entrance) -> None:
        entrance.sensor, entrance.clear_event = "clear", None
        self._close(entrance)
        self._let_out(entrance)

    # ---- cars ----------------------------------------------------------------------------

    def goto(self, car: Car, floor: int, up: bool) -> None:
        """The controller sends ``car`` to ``floor``, to light ``up`` or down on arrival."""
        car.next_up = up
        car.destination = floor
        if car.location is None:
            self._head_for(car, floor)

    def _head_for(self, car: Car, floor: int) -> None:
        """``setDestinationHeight``: redirect, or arrive at once when already there."""
        car.height = self.height_of(car)
        self.queue.cancel(car.arrival_event)
        car.arrival_event = None
        target = (floor - 1) * FLOOR_HEIGHT
        if car.height == target:
            self._arrive(car)
            return
        car.departed_at, car.departed_from = self.queue.now, car.height
        travel = int(abs(car.height - target) / CAR_RATE)
        car.arrival_event = self.queue.at(self.queue.now + travel, lambda: self._arrive(car))

    def _arrive(self, car: Car) -> None:
        floor = car.destination
        assert floor is not None
        car.height = (floor - 1) * FLOOR_HEIGHT
        car.arrival_event = None
        car.location, car.destination = floor, None
        if floor in car.requested:
            car.requested.remove(floor)
        entrance = self.entrances[(floor, car.number)]
        self._open(entrance)
        entrance.up, entrance.down = car.next_up, not car.next_up
        entrance.leaving += [p for p in car.people if p.destination == floor]
        self._let_out(entrance)

    def _undock(self, car: Car) -> None:
        car.location = None
        if car.destination is not None:
            self._head_for(car, car.destination)
