"""The elevator environment: cars as entities, each percept's timing, goto and its refusals,
riders carried by the simulation, seeded riders, and the example cars serving everyone."""

from __future__ import annotations

from pathlib import Path

import pytest

from goalagent.eis import ActionRefused, ManagementException
from goalagent.eis.envs.elevator.environment import Elevator
from goalagent.eis.envs.elevator.scenarios import Settings, build
from goalagent.eis.terms import Action
from goalagent.mas import MultiAgentSystem

EXAMPLES = Path(__file__).resolve().parents[4] / "agents" / "examples"


def running(**params: object) -> Elevator:
    """A started building with agent ``a0`` on car0, ``a1`` on car1, ..."""
    env = Elevator()
    env.init({"simulation": "Three Person Elevator", "floors": 6, "cars": 1,
              "timefactor": 3, **params})
    env.start()
    for entity in env.entities():
        agent = entity.replace("car", "a")
        env.register_agent(agent)
        env.associate_entity(agent, entity)
    return env


def look(env: Elevator, agent: str = "a0") -> list[str]:
    (percepts,) = env.get_all_percepts(agent).values()
    return [str(p) for p in percepts]


def named(seen: list[str], *names: str) -> list[str]:
    return [p for p in seen if p.split("(")[0] in names]


def goto(env: Elevator, floor: object, direction: str, agent: str = "a0") -> None:
    env.perform_action(agent, Action.of("goto", floor, direction))


def test_cars_are_entities() -> None:
    env = running(cars=3)
    assert env.entities() == ["car0", "car1", "car2"]
    assert {env.entity_type(e) for e in env.entities()} == {"car"}


def test_once_and_always_percepts() -> None:
    env = running()
    first = look(env)
    assert first == ["atFloor(1)", "doorState(closed)", "carPosition(1.0)", "capacity(8)",
                     "people(0)", "floorCount(6)", "timefactor(3)"]
    second = look(env)  # the three riders have pressed their buttons by now
    assert second == ["atFloor(1)", "carPosition(1.0)", "fButtonOn(2,up)", "fButtonOn(4,down)",
                      "timefactor(3)"]


def test_a_trip_door_states_people_and_buttons() -> None:
    env = running()
    look(env), look(env)
    goto(env, 2, "up")
    cycles = [look(env) for _ in range(30)]
    doors = [d for c in cycles for d in named(c, "doorState")]
    assert doors[:4] == ["doorState(opening)", "doorState(opened)", "doorState(closing)",
                         "doorState(closed)"]
    travelling = [c for c in cycles if not named(c, "atFloor")]
    assert travelling and all(1.0 < float(named(c, "carPosition")[0][12:-1]) < 2.0
                              for c in travelling)
    people = [p for c in cycles for p in named(c, "people")]
    assert people == ["people(1)", "people(2)"]  # two riders boarded at floor 2, going up
    assert "eButtonOn(3)" in cycles[-1] and "eButtonOn(5)" in cycles[-1]
    assert "fButtonOn(2,up)" not in cycles[-1] and "fButtonOn(4,down)" in cycles[-1]


def test_riders_only_board_in_their_direction() -> None:
    env = running()
    look(env), look(env)
    goto(env, 2, "down")  # the riders on floor 2 want to go up
    for _ in range(40):
        seen = look(env)
    assert "people(1)" not in seen and env.building.cars[0].people == []
    assert "fButtonOn(2,up)" in seen


@pytest.mark.parametrize(
    ("floor", "direction", "reason"),
    [(7, "up", "there is no floor 7"), (0, "down", "there is no floor 0"),
     (2.5, "up", "there is no floor 2.5"), (2, "sideways", "must be up or down")],
)
def test_refused_gotos_change_nothing(floor: object, direction: str, reason: str) -> None:
    env = running()
    look(env)
    car = env.building.cars[0]
    before = (car.destination, car.next_up, env.building.queue.now)
    with pytest.raises(ActionRefused, match=reason):
        goto(env, floor, direction)
    assert (car.destination, car.next_up, env.building.queue.now) == before


def test_a_float_floor_number_is_accepted() -> None:
    env = running()
    goto(env, 3.0, "up")
    assert env.building.cars[0].destination == 3


def test_seeded_random_riders_repeat() -> None:
    def riders(seed: int) -> list[tuple[int, int | None]]:
        building = build("Random Rider Insertion", Settings(randomseed=seed, people=15))
        building.queue.run_until(60_000)
        return [(p.floor, p.destination) for p in building.people]

    assert riders(3) == riders(3)
    assert riders(3) != riders(4)
    assert all(start != dest for start, dest in riders(3))


def test_rush_hours() -> None:
    morning = build("Morning Traffic Rider Insertion",
                    Settings(floors=4, npeopleperfloor=2, insertiontimehr=0.01))
    evening = build("Evening Traffic Rider Insertion",
                    Settings(floors=4, npeopleperfloor=2, insertiontimehr=0.01))
    for building in (morning, evening):
        building.queue.run_until(40_000)
        assert len(building.people) == 6
    assert {p.floor for p in morning.people} == {1}
    assert {p.destination for p in evening.people} == {1}


@pytest.mark.parametrize(
    ("params", "message"),
    [
        ({"simulation": "Lunch Rush"}, "no simulation 'Lunch Rush'"),
        ({"controller": "MetaController"}, "only the EIS controller"),
        ({"floors": 0}, "floors must be at least 1"),
        ({"lifts": 2}, "no init parameter 'lifts'"),
        ({"simulation": "Three Person Elevator", "floors": 3}, "needs floor 5"),
    ],
)
def test_bad_init_parameters(params: dict, message: str) -> None:
    with pytest.raises(ManagementException, match=message):
        Elevator().init({"floors": 6, **params})


def test_goal_programs_parameter_spelling_is_accepted() -> None:
    env = Elevator()
    env.init({"Simulation": "Random Rider Insertion", "Floors": 10, "Cars": 3,
              "RandomSeed": 635359, "Capacity": 8, "People": 20, "InsertionTime": 50000,
              "TimeFactor": 0, "Controller": "EIS Controller", "InsertionTimeHr": 0.3,
              "StandardDev": 1, "NPeoplePerFloor": 8, "Insert2ndReqAt": 29000})
    assert env.entities() == ["car0", "car1", "car2"] and env.round_time == 100


def test_snapshots(tmp_path: Path) -> None:
    env = running(snapshots=str(tmp_path))
    look(env), look(env)
    assert [p.name for p in tmp_path.iterdir()] == ["elevator-000001.png"]


def test_the_example_cars_serve_every_rider() -> None:
    system = MultiAgentSystem.from_mas_file(EXAMPLES / "elevator.mas2g")
    try:
        summaries = system.run(max_cycles=400)
        building = system.environment.building
        assert len(building.people) == 3 and all(p.arrived for p in building.people)
        assert [(s.name, s.status) for s in summaries] == [
            ("car", "terminated"), ("car2", "terminated")]
    finally:
        system.close()
