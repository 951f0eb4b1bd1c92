"""EIS Environment base: state machine, entities and agents, listeners, percepts and actions."""

from __future__ import annotations

import pytest

from goalagent.eis import (
    ActException,
    ActExceptionKind,
    Action,
    AgentException,
    EntityException,
    Environment,
    EnvironmentState,
    ManagementException,
    Numeral,
    Parameter,
    PerceiveException,
    Percept,
    RelationException,
)

S = EnvironmentState


class Counter(Environment):
    """A tiny hand-written environment: each entity has a counter that ``inc`` raises."""

    name = "counter"

    def __init__(self) -> None:
        super().__init__()
        self.hooks: list[str] = []

    def do_init(self, params: dict[str, Parameter]) -> None:
        start = params.get("start", Numeral(0))
        assert isinstance(start, Numeral)
        self.counts: dict[str, int | float] = {}
        for entity in ("e1", "e2"):
            self.counts[entity] = start.value
            if entity not in self.entities():
                self.add_entity(entity, "counter")

    def do_start(self) -> None:
        self.hooks.append("start")

    def do_pause(self) -> None:
        self.hooks.append("pause")

    def do_kill(self) -> None:
        self.hooks.append("kill")

    def percepts_for_entity(self, entity: str) -> list[Percept]:
        return [Percept.of("count", self.counts[entity])]

    def perform_entity_action(self, entity: str, action: Action) -> Percept | None:
        if action.name != "inc":
            raise ActException(f"no action {action.name}", ActExceptionKind.UNKNOWN_ACTION)
        self.counts[entity] += 1
        return Percept.of("done", entity)


class Recorder:
    """A listener that records every call it gets."""

    def __init__(self) -> None:
        self.calls: list[tuple] = []

    def handle_state_change(self, state: EnvironmentState) -> None:
        self.calls.append(("state", state))

    def handle_new_entity(self, entity: str, type: str) -> None:
        self.calls.append(("new", entity, type))

    def handle_free_entity(self, entity: str, agents: list[str]) -> None:
        self.calls.append(("free", entity, agents))

    def handle_deleted_entity(self, entity: str, agents: list[str]) -> None:
        self.calls.append(("deleted", entity, agents))

    def handle_percept(self, agent: str, percept: Percept) -> None:
        self.calls.append(("percept", agent, str(percept)))


@pytest.fixture
def env() -> Counter:
    """A running counter environment with agent ``ag`` on entity ``e1``."""
    environment = Counter()
    environment.init({})
    environment.start()
    environment.register_agent("ag")
    environment.associate_entity("ag", "e1")
    return environment


def test_life_cycle_and_hooks() -> None:
    environment = Counter()
    recorder = Recorder()
    environment.attach_environment_listener(recorder)
    assert environment.state is S.INITIALIZING
    environment.init({"start": Numeral(5)})
    assert environment.state is S.PAUSED
    environment.start()
    environment.pause()
    environment.start()
    environment.start()  # staying in a state is a no-op
    environment.kill()
    environment.kill()
    assert environment.hooks == ["start", "pause", "start", "kill"]
    states = [call[1] for call in recorder.calls if call[0] == "state"]
    assert states == [S.PAUSED, S.RUNNING, S.PAUSED, S.RUNNING, S.KILLED]
    assert ("new", "e1", "counter") in recorder.calls


def test_initializing_can_start_pause_or_be_killed_directly() -> None:
    environment = Counter()
    environment.start()  # initialises with no parameters on the way
    assert environment.state is S.RUNNING
    assert environment.entities() == ["e1", "e2"]
    assert environment.hooks == ["start"]
    paused = Counter()
    paused.pause()  # the same as init({})
    assert paused.state is S.PAUSED and paused.entities() == ["e1", "e2"]
    assert paused.hooks == []
    other = Counter()
    other.kill()  # nothing was built, so there is nothing to release
    assert other.state is S.KILLED
    assert other.hooks == []


@pytest.mark.parametrize(
    ("setup", "move", "message"),
    [
        (["kill"], "start", "cannot go from killed to running .*killed; create a new one"),
        (["kill"], "pause", "cannot go from killed to paused"),
        (["init"], "init", "already initialised .*use reset"),
        ([], "reset", "cannot be reset while initializing .*init"),
        (["init", "kill"], "reset", "cannot be reset while killed"),
    ],
)
def test_invalid_transitions_are_clear_errors(
    setup: list[str], move: str, message: str
) -> None:
    environment = Counter()
    for step in setup:
        getattr(environment, step)()
    before = environment.state
    with pytest.raises(ManagementException, match=message):
        getattr(environment, move)()
    assert environment.state is before


def test_reset_rebuilds_with_merged_parameters(env: Counter) -> None:
    env.perform_action("ag", Action("inc"))
    env.reset({"start": Numeral(10)})
    assert env.state is S.PAUSED
    assert env.params == {"start": Numeral(10)}
    assert env.get_all_percepts("ag") == {"e1": [Percept.of("count", 10)]}
    assert env.associated_entities("ag") == ["e1"]


def test_entities_and_types(env: Counter) -> None:
    assert env.entities() == ["e1", "e2"]
    assert env.entity_type("e2") == "counter"
    with pytest.raises(EntityException, match="has no entity 'nope' .*e1, e2"):
        env.entity_type("nope")
    with pytest.raises(EntityException, match="already has entity 'e1'"):
        env.add_entity("e1")


def test_association_and_freeing(env: Counter) -> None:
    recorder = Recorder()
    env.attach_environment_listener(recorder)
    env.register_agent("other")
    env.associate_entity("other", "e1")
    env.associate_entity("other", "e2")
    assert env.associated_agents("e1") == ["ag", "other"]
    assert env.associated_entities("other") == ["e1", "e2"]
    assert env.free_entities() == []
    env.free_pair("other", "e1")  # ag still has e1: not free, no event
    assert recorder.calls == []
    env.free_agent("other")  # e2 is now free
    assert recorder.calls == [("free", "e2", ["other"])]
    assert env.free_entities() == ["e2"]
    env.free_entity("e1")
    assert recorder.calls[-1] == ("free", "e1", ["ag"])
    assert env.associated_entities("ag") == []
    with pytest.raises(RelationException, match="not associated with any agent"):
        env.free_entity("e1")


def test_association_errors(env: Counter) -> None:
    with pytest.raises(RelationException, match="agent 'ghost' is not registered"):
        env.associate_entity("ghost", "e1")
    with pytest.raises(RelationException, match="no entity 'e9'"):
        env.associate_entity("ag", "e9")
    with pytest.raises(RelationException, match="already associated"):
        env.associate_entity("ag", "e1")
    with pytest.raises(RelationException, match="not associated with 'e2'"):
        env.free_pair("ag", "e2")
    with pytest.raises(AgentException, match="already registered"):
        env.register_agent("ag")
    with pytest.raises(AgentException, match="not registered"):
        env.unregister_agent("ghost")


def test_unregister_frees_entities(env: Counter) -> None:
    recorder = Recorder()
    env.attach_environment_listener(recorder)
    env.unregister_agent("ag")
    assert env.agents() == []
    assert recorder.calls == [("free", "e1", ["ag"])]
    assert env.free_entities() == ["e1", "e2"]


def test_deleting_an_entity_tells_listeners_its_agents(env: Counter) -> None:
    recorder = Recorder()
    env.attach_environment_listener(recorder)
    env.delete_entity("e1")
    assert recorder.calls == [("deleted", "e1", ["ag"])]
    assert env.entities() == ["e2"]
    assert env.associated_entities("ag") == []


def test_listeners_may_leave_methods_out_and_can_be_detached(env: Counter) -> None:
    class OnlyNew:
        def __init__(self) -> None:
            self.seen: list[str] = []

        def handle_new_entity(self, entity: str, type: str) -> None:
            self.seen.append(entity)

    only_new = OnlyNew()
    env.attach_environment_listener(only_new)
    env.pause()
    env.add_entity("e3", "counter")
    env.delete_entity("e3")
    env.detach_environment_listener(only_new)
    env.add_entity("e4")
    assert only_new.seen == ["e3"]


def test_pushed_percepts_reach_agent_listeners(env: Counter) -> None:
    env.register_agent("b")
    env.associate_entity("b", "e2")
    listener_a, listener_b = Recorder(), Recorder()
    env.attach_agent_listener("ag", listener_a)
    env.attach_agent_listener("b", listener_b)
    env.notify_agents(Percept.of("bell"))
    env.notify_agents(Percept.of("ping", 1), "b")
    env.notify_agents_via_entity(Percept.of("via", "e1"), "e1")
    assert listener_a.calls == [("percept", "ag", "bell"), ("percept", "ag", "via(e1)")]
    assert listener_b.calls == [("percept", "b", "bell"), ("percept", "b", "ping(1)")]
    env.detach_agent_listener("b", listener_b)
    env.notify_agents(Percept.of("bell"), "b")
    assert len(listener_b.calls) == 2
    with pytest.raises(AgentException, match="'ghost' is not registered"):
        env.notify_agents(Percept.of("bell"), "ghost")
    with pytest.raises(AgentException, match="'ghost' is not registered"):
        env.attach_agent_listener("ghost", Recorder())


def test_percepts_per_entity(env: Counter) -> None:
    env.associate_entity("ag", "e2")
    assert env.get_all_percepts("ag") == {
        "e1": [Percept.of("count", 0)],
        "e2": [Percept.of("count", 0)],
    }
    assert env.get_all_percepts("ag", "e2") == {"e2": [Percept.of("count", 0)]}
    env.register_agent("idle")
    assert env.get_all_percepts("idle") == {}


def test_percept_errors(env: Counter) -> None:
    with pytest.raises(PerceiveException, match="'ghost' is not registered"):
        env.get_all_percepts("ghost")
    with pytest.raises(PerceiveException, match="not associated with entity 'e2'"):
        env.get_all_percepts("ag", "e2")
    with pytest.raises(PerceiveException, match="no entity 'e7'"):
        env.get_all_percepts("ag", "e7")
    fresh = Counter()
    fresh.register_agent("a")
    with pytest.raises(PerceiveException, match="no percepts while initializing"):
        fresh.get_all_percepts("a")


def test_actions_return_per_entity_results(env: Counter) -> None:
    assert env.perform_action("ag", Action("inc")) == {"e1": Percept.of("done", "e1")}
    assert env.get_all_percepts("ag") == {"e1": [Percept.of("count", 1)]}


@pytest.mark.parametrize(
    ("agent", "entities", "kind", "message"),
    [
        ("ghost", (), ActExceptionKind.NOT_REGISTERED, "agent 'ghost' is not registered"),
        ("ag", ("e2",), ActExceptionKind.WRONG_ENTITY, "not associated with entity 'e2'"),
        ("ag", ("e9",), ActExceptionKind.WRONG_ENTITY, "no entity 'e9'"),
        ("idle", (), ActExceptionKind.NO_ENTITIES, "'idle' has no entity"),
    ],
)
def test_actions_for_unknown_agents_or_entities_leave_the_world_alone(
    env: Counter, agent: str, entities: tuple[str, ...], kind: ActExceptionKind, message: str
) -> None:
    env.register_agent("idle")
    with pytest.raises(ActException, match=message) as caught:
        env.perform_action(agent, Action("inc"), *entities)
    assert caught.value.kind is kind
    assert env.counts == {"e1": 0, "e2": 0}
    assert env.state is S.RUNNING
    assert env.perform_action("ag", Action("inc")) == {"e1": Percept.of("done", "e1")}


def test_actions_need_a_running_environment(env: Counter) -> None:
    env.pause()
    with pytest.raises(ActException, match="is paused; inc was not performed") as caught:
        env.perform_action("ag", Action("inc"))
    assert caught.value.kind is ActExceptionKind.NOT_RUNNING
    assert env.counts["e1"] == 0
    assert env.get_all_percepts("ag") == {"e1": [Percept.of("count", 0)]}


def test_the_base_class_supports_no_actions() -> None:
    environment = Environment()
    environment.add_entity("x")
    environment.register_agent("a")
    environment.associate_entity("a", "x")
    environment.init({})
    environment.start()
    with pytest.raises(ActException, match="supports no actions") as caught:
        environment.perform_action("a", Action("go"))
    assert caught.value.kind is ActExceptionKind.UNKNOWN_ACTION
    assert environment.get_all_percepts("a") == {"x": []}
