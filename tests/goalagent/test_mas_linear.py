"""Launching and closing a system on an environment's entities is O(N) (issue 29): counted in
operations, not timed. A system of N agents on N entities makes the environment look at
O(N) agents and entities in all; a scan of every agent or entity per launch (as asking for
all free entities on each new entity, or walking the agents for one without a body, did)
makes it O(N²) and fails the ratio below by a factor of four."""

from __future__ import annotations

import io
from _collections_abc import dict_items, dict_keys, dict_values
from collections.abc import Iterator
from pathlib import Path
from typing import TypeVar

import pytest

from goalagent.eis.interface import Environment
from goalagent.eis.terms import Parameter
from goalagent.mas import MultiAgentSystem

K = TypeVar("K")
V = TypeVar("V")
SMALL, LARGE = 40, 160  # linear work grows 4x from one to the other, quadratic 16x

AGENT = """
init module { beliefs { n(0). } }
main module { program { if bel(n(N), M is N + 1) then delete(n(N)) + insert(n(M)). } }
"""


class Visits:
    """How many agents and entities the environment's bookkeeping looked at."""

    count = 0


class CountingDict(dict[K, V]):
    """A dict that counts every element a walk over it visits."""

    def __iter__(self) -> Iterator[K]:
        Visits.count += len(self)
        return super().__iter__()

    def items(self) -> dict_items[K, V]:
        Visits.count += len(self)
        return super().items()

    def values(self) -> dict_values[K, V]:
        Visits.count += len(self)
        return super().values()

    def keys(self) -> dict_keys[K, V]:
        Visits.count += len(self)
        return super().keys()


class CountingEnvironment(Environment):
    """``bots`` entities of type bot, its relations kept in counting dicts; each query a
    system may make per agent counts one visit too."""

    name = "counting"

    def __init__(self) -> None:
        super().__init__()
        self._agents: dict[str, list[str]] = CountingDict()
        self._entities: dict[str, str] = CountingDict()
        self._holders: dict[str, dict[str, None]] = CountingDict()

    def do_init(self, params: dict[str, Parameter]) -> None:
        self.bots = int(params["bots"].value)  # type: ignore[union-attr,arg-type]

    def do_start(self) -> None:
        for index in range(self.bots):
            self.add_entity(f"bot{index}", "bot")

    def associated_entities(self, agent: str) -> list[str]:
        Visits.count += 1
        return super().associated_entities(agent)

    def associated_agents(self, entity: str) -> list[str]:
        Visits.count += 1
        return super().associated_agents(entity)


def visits(tmp_path: Path, bots: int, launch: str) -> tuple[int, int]:
    """The visits of building a system of ``bots`` agents on as many entities (``launch``:
    its agent file and launch policy), and of running a round and closing it."""
    (tmp_path / "bot.goal").write_text(AGENT)
    (tmp_path / "sys.mas2g").write_text(f"""
        environment {{ env = "{__name__}:CountingEnvironment". init = [bots = {bots}]. }}
        {launch.format(bots=bots)}
    """)
    Visits.count = 0
    system = MultiAgentSystem.from_mas_file(tmp_path / "sys.mas2g", output=io.StringIO(),
                                            warn=lambda message: None)
    built = Visits.count
    environment = system.environment
    assert environment is not None
    assert len(system.agents) == bots
    assert all(environment.associated_entities(agent.name) for agent in system.agents)
    assert not environment.free_entities()
    Visits.count = 0
    system.run(max_cycles=1)
    system.close()
    return built, Visits.count


ENTITY_LAUNCH = """agentfiles {{ "bot.goal" [name = b]. }}
        launchpolicy {{ when type = bot launch * : b. }}"""
WAITING_AGENTS = """agentfiles {{ "bot.goal" [name = b, number = {bots}]. }}
        launchpolicy {{ launch worker : b. }}"""


@pytest.mark.parametrize("launch", [ENTITY_LAUNCH, WAITING_AGENTS],
                         ids=["launched-on-entities", "waiting-for-entities"])
def test_building_running_and_closing_visit_each_agent_a_bounded_number_of_times(
        tmp_path: Path, launch: str) -> None:
    (tmp_path / "small").mkdir()
    (tmp_path / "large").mkdir()
    built_small, rest_small = visits(tmp_path / "small", SMALL, launch)
    built_large, rest_large = visits(tmp_path / "large", LARGE, launch)
    assert built_large <= 8 * LARGE, f"building {LARGE} agents: {built_large} visits"
    assert built_large <= 5 * max(built_small, 1), (built_small, built_large)
    assert rest_large <= 8 * LARGE, f"a round and closing {LARGE}: {rest_large} visits"
    assert rest_large <= 5 * max(rest_small, 1), (rest_small, rest_large)


def test_the_first_agent_without_an_entity_is_the_earliest_registered() -> None:
    environment = CountingEnvironment()
    for entity in ("e1", "e2", "e3"):
        environment.add_entity(entity)
    for agent in ("a", "b", "c"):
        environment.register_agent(agent)
    assert environment.first_agent_without_entity() == "a"
    environment.associate_entity("a", "e1")
    environment.associate_entity("b", "e2")
    assert environment.first_agent_without_entity() == "c"
    environment.associate_entity("c", "e3")
    assert environment.first_agent_without_entity() is None
    environment.associate_entity("a", "e2")  # b and a share e2; b loses it, e2 stays held
    environment.free_pair("b", "e2")
    assert environment.first_agent_without_entity() == "b"
    assert environment.associated_agents("e2") == ["a"]
    environment.free_entity("e1")  # a keeps e2
    environment.delete_entity("e2")  # a has none now; it registered before b
    assert environment.first_agent_without_entity() == "a"
    assert environment.is_free("e1") and not environment.is_free("e3")
    assert not environment.is_free("e2")  # gone
    environment.unregister_agent("a")
    assert environment.first_agent_without_entity() == "b"
    environment.register_agent("a")  # again: now the latest
    environment.associate_entity("b", "e1")
    assert environment.first_agent_without_entity() == "a"
    assert environment.free_entities() == []
