"""The elevator simulator as an EIS environment, with the GOAL controller's vocabulary.

One entity per car, ``car0``, ``car1``, ... of type ``car``. Percepts (``GOALController.
sendPercepts``): ``atFloor(F)`` while at a floor, ``doorState(S)`` (opening, opened, closing,
closed) when it changes, ``carPosition(P)`` (1.0 = ground floor) always, ``fButtonOn(F, up|down)``
for every lit call button, ``eButtonOn(F)`` for every floor asked for inside the car,
``people(N)`` when it changes, ``capacity(N)`` and ``floorCount(N)`` once, ``timefactor(T)``
always. Action ``goto(Floor, up|down)``: go to the floor and light that direction on arrival
(a new ``goto`` replaces the old one; a car with open doors leaves once they are closed).

Time: each round of agent cycles advances the simulation by 100 ms x 2^timefactor, the Java
simulator's clock step.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import fields

from goalagent.eis.envs.elevator.building import Building, Car
from goalagent.eis.envs.elevator.render import draw_building
from goalagent.eis.envs.elevator.scenarios import Settings, build
from goalagent.eis.envs.filters import Filter, PerceptFilter
from goalagent.eis.envs.support import (
    RoundClock,
    SnapshotWriter,
    check_known,
    float_param,
    int_param,
    text_param,
    write_png,
)
from goalagent.eis.exceptions import ActionRefused, ManagementException
from goalagent.eis.pyenv import PerceptLike, PythonEnvironment, action
from goalagent.eis.terms import Percept

CONTROLLERS = ("EIS Controller", "GOAL Controller")
KNOWN_PARAMETERS = {
    "simulation": "which simulation (its description in the Java simulator)",
    **{f.name: f"a simulator setting (Simulator.Keys), default {f.default}"
       for f in fields(Settings)},
    "controller": "must be the EIS (GOAL) controller",
    "timefactor": "simulated time per round: 100 ms x 2^timefactor",
    "snapshots": "directory for one PNG snapshot per round",
}
CLOCK_STEP = 100


class Elevator(PythonEnvironment):
    """Cars in a building with riders; each car is steered by an agent with ``goto``."""

    name = "elevator"
    default_entity_type = "car"

    @classmethod
    def init_parameters(cls) -> dict[str, str]:
        return KNOWN_PARAMETERS

    @classmethod
    def init_key(cls, key: str) -> str:
        return key.lower()  # read in any case, as GOAL programs write them

    def on_init(self, params: dict[str, object]) -> None:
        """Build the chosen simulation from the settings."""
        params = {key.lower(): value for key, value in params.items()}
        check_known(self.name, params, KNOWN_PARAMETERS)
        controller = text_param(self.name, params, "controller", CONTROLLERS[0])
        if controller not in CONTROLLERS:
            raise ManagementException(
                f"elevator: only the EIS controller lets agents drive the cars, "
                f"got controller {controller!r}"
            )
        values: dict[str, object] = {}
        for spec in fields(Settings):
            if spec.type == "float":
                values[spec.name] = float_param(self.name, params, spec.name, spec.default)
            else:
                values[spec.name] = int_param(self.name, params, spec.name, spec.default,
                                              minimum=0 if spec.name == "randomseed" else None)
        settings = Settings(**values)
        for key in ("floors", "cars", "capacity", "standarddev", "insertiontime"):
            if getattr(settings, key) < 1:
                raise ManagementException(f"elevator: {key} must be at least 1")
        simulation = text_param(self.name, params, "simulation", "Random Rider Insertion")
        self.building: Building = build(simulation, settings)
        self.simulation = simulation
        self.timefactor = int_param(self.name, params, "timefactor", 0, minimum=0, maximum=16)
        self.filter = PerceptFilter()
        self.clock = RoundClock()
        self.cars = {f"car{car.number}": car for car in self.building.cars}
        self.snapshots = None
        if params.get("snapshots") is not None:
            self.snapshots = SnapshotWriter(text_param(self.name, params, "snapshots", ""),
                                            "elevator")

    def initial_entities(self) -> dict[str, str]:
        """``car0`` ... of type ``car``."""
        return {name: "car" for name in self.cars}

    @property
    def round_time(self) -> int:
        """Simulated milliseconds per round."""
        return CLOCK_STEP * 2 ** self.timefactor

    def advance(self, rounds: int = 1) -> None:
        """Run ``rounds`` rounds of simulated time."""
        queue = self.building.queue
        queue.run_until(queue.now + rounds * self.round_time)

    def draw(self, figure: object) -> None:
        draw_building(figure, self.building, self.clock.rounds)

    def snapshot(self, path: str) -> None:
        """Write a PNG of the building now to ``path`` (atomically)."""
        write_png(path, self.draw)

    def percepts(self, entity: str) -> Iterable[PerceptLike]:
        """The car's percepts this cycle, as the GOAL controller sends them."""
        if self.clock.perceive(entity):
            self.advance()
            if self.snapshots is not None:
                self.snapshots.write(self.clock.rounds, self.draw)
        car = self.cars[entity]
        building = self.building
        floor = building.floor_of(car)
        door = building.entrances[(floor, car.number)].door if floor is not None else "closed"
        every: list[tuple[str, Filter, list[tuple]]] = [
            ("atFloor", Filter.ALWAYS, [(floor,)] if floor is not None else []),
            ("doorState", Filter.ON_CHANGE, [(door,)]),
            ("carPosition", Filter.ALWAYS, [(1.0 + building.height_of(car) / 10.0,)]),
            ("fButtonOn", Filter.ALWAYS, self._calls()),
            ("eButtonOn", Filter.ALWAYS, [(f,) for f in car.requested]),
            ("capacity", Filter.ONCE, [(car.capacity,)]),
            ("people", Filter.ON_CHANGE, [(len(car.people),)]),
            ("floorCount", Filter.ONCE, [(building.floors,)]),
            ("timefactor", Filter.ALWAYS, [(self.timefactor,)]),
        ]
        result: list[Percept] = []
        for name, kind, values in every:
            result += self.filter.percepts(entity, name, kind, values)
        return result

    def _calls(self) -> list[tuple[int, str]]:
        calls: list[tuple[int, str]] = []
        for floor in range(1, self.building.floors + 1):
            if self.building.call_up[floor]:
                calls.append((floor, "up"))
            if self.building.call_down[floor]:
                calls.append((floor, "down"))
        return calls

    @action("goto")
    def goto(self, entity: str, floor: float, direction: str) -> None:
        """Go to ``floor`` and light ``direction`` (up or down) on arrival."""
        car: Car = self.cars[entity]
        what = f"goto({floor:g},{direction})"
        if direction not in ("up", "down"):
            raise ActionRefused(f"{what}: the direction must be up or down")
        if not float(floor).is_integer() or not 1 <= floor <= self.building.floors:
            raise ActionRefused(f"{what}: there is no floor {floor:g} (floors 1 to "
                                f"{self.building.floors})")
        self.building.goto(car, int(floor), direction == "up")
