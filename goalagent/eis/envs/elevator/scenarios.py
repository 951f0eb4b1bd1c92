"""The elevator simulator's simulations: who appears where, wanting to go where, when.

Each of the Java simulator's simulations (selected by its description, the ``simulation`` init
parameter) as a function filling a ``Building``. The random ones draw with
``java.util.Random(randomseed)`` in the Java simulator's order, so a seed gives the riders
the Java simulator gives. Java's ``float`` arithmetic is done as IEEE single precision by
``_f32``: each operation computed in double and rounded to single gives the single-precision
result exactly (double has more than twice single's precision), so the standard library
does what numpy's float32 did and the language needs no numpy.
"""

from __future__ import annotations

import struct
from collections.abc import Callable
from dataclasses import dataclass

from goalagent.eis.envs.elevator.building import Building
from goalagent.eis.envs.javarandom import JavaRandom
from goalagent.eis.exceptions import ManagementException


@dataclass(frozen=True)
class Settings:
    """The simulator's parameters (``Simulator.Keys``) with their defaults."""

    floors: int = 10
    cars: int = 3
    capacity: int = 8
    people: int = 20
    npeopleperfloor: int = 20
    insertiontime: int = 50000
    insertiontimehr: float = 1.0
    updestination: int = 3
    downdestination: int = 2
    standarddev: int = 1
    randomseed: int = 635359
    insert2ndreqat: int = 29000


def _trip(building: Building, start: int, destination: int, time: int) -> None:
    """A person on floor index ``start`` who wants floor index ``destination`` at ``time``."""
    for index in (start, destination):
        if not 0 <= index < building.floors:
            raise ManagementException(
                f"elevator: this simulation needs floor {index + 1}; the building has "
                f"{building.floors} floors"
            )
    person = building.add_person(start + 1)
    building.queue.at(time, lambda: building.call(person, destination + 1))


def _random(s: Settings) -> Building:
    building = Building(s.floors, s.cars, s.capacity)
    if s.floors < 2:
        raise ManagementException("elevator: random riders need at least 2 floors")
    random = JavaRandom(s.randomseed)
    for _ in range(s.people):
        start = random.next_int_below(s.floors)
        destination = start
        while destination == start:
            destination = random.next_int_below(s.floors)
        _trip(building, start, destination, random.next_int_below(s.insertiontime))
    return building


def _gaussian(random: JavaRandom, deviation: int, single: bool) -> float:
    """A normal draw scaled by 1/deviation, redrawn until in [-1, 1] (``getGaussian``)."""
    while True:
        value = random.next_gaussian() / deviation
        if single:
            value = _f32(value)
        if -1.0 <= value <= 1.0:
            return value


def _rush(s: Settings, morning: bool) -> Building:
    """Morning: everyone from the ground floor up; evening: everyone down to it."""
    building = Building(s.floors, s.cars, 8)
    random = JavaRandom(s.randomseed)
    for floor in range(1, s.floors):
        for _ in range(s.npeopleperfloor):
            if morning:
                fraction = (_gaussian(random, s.standarddev, False) + 1) / 2
                time = int(fraction * (_f32(s.insertiontimehr) * 3600.0 * 1000.0))
                _trip(building, 0, floor, time)
            else:
                fraction = _f32(_f32(_gaussian(random, s.standarddev, True) + 1) / 2)
                hours = _f32(s.insertiontimehr)
                time = int(_f32(_f32(_f32(fraction * hours) * 3600) * 1000))
                _trip(building, floor, 0, time)
    return building


def _f32(value: float) -> float:
    """``value`` rounded to IEEE single precision (Java's ``float``)."""
    return struct.unpack("f", struct.pack("f", value))[0]


def _scripted(floors: int | None, cars: int | None, capacity: int,
              trips: Callable[[Settings], list[tuple[int, int, int]]]
              ) -> Callable[[Settings], Building]:
    """A fixed scenario: (start index, destination index, time) trips."""

    def build(s: Settings) -> Building:
        building = Building(floors or s.floors, cars or s.cars, capacity)
        for start, destination, time in trips(s):
            _trip(building, start, destination, time)
        return building

    return build


SIMULATIONS: dict[str, Callable[[Settings], Building]] = {
    "Random Rider Insertion": _random,
    "Morning Traffic Rider Insertion": lambda s: _rush(s, morning=True),
    "Evening Traffic Rider Insertion": lambda s: _rush(s, morning=False),
    "Three Person Trip Bug": _scripted(6, 1, 8, lambda s: [(3, 0, 0), (1, 2, s.insert2ndreqat)]),
    "Three Person Elevator": _scripted(None, None, 8, lambda s: [(1, 2, 0), (1, 4, 0), (3, 1, 0)]),
    "Three Person Two Elevator": _scripted(None, None, 8,
                                           lambda s: [(3, 1, 0), (1, 3, 0), (2, 4, 0)]),
    "Elevator Travels Up To Process A Down Request": _scripted(None, None, 8,
                                                                lambda s: [(3, 1, 0)]),
    "People Going Different Directions, Only One Car": _scripted(
        None, None, 8, lambda s: [(1, s.updestination - 1, 0), (3, s.downdestination - 1, 0)]),
}


def build(simulation: str, settings: Settings) -> Building:
    """The building of ``simulation`` (its description, as in the Java simulator)."""
    if simulation == "ticket 492 test scenario":
        maker = _scripted(None, None, settings.capacity,
                          lambda s: [(0, 1, 0), (1, 2, 18000), (1, 2, 22000)])
    elif simulation in SIMULATIONS:
        maker = SIMULATIONS[simulation]
    else:
        known = ", ".join([*SIMULATIONS, "ticket 492 test scenario"])
        raise ManagementException(f"elevator: no simulation {simulation!r} (simulations: {known})")
    return maker(settings)
