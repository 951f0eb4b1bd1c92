"""Any action or init parameter an agent program can produce gets a clean EIS error or works."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from goalagent.eis import (
    ActException,
    Action,
    EnvironmentInterfaceException,
    Function,
    Identifier,
    Numeral,
    ParameterList,
    load_environment,
)

ENVS = ["blocksworld", "towerworld", "printer"]
WORDS = ["a", "b", "c", "table", "z", "true", "", "Hello world"]
leaves = st.one_of(
    st.builds(Identifier, st.sampled_from(WORDS), st.booleans()),
    st.builds(Numeral, st.one_of(st.integers(-3, 12), st.floats(allow_nan=False))),
)
params = st.recursive(
    leaves,
    lambda inner: st.one_of(
        st.builds(ParameterList, st.lists(inner, max_size=3).map(tuple)),
        st.builds(Function, st.sampled_from(["on", "f", "block"]), st.lists(inner, max_size=2)),
    ),
    max_leaves=6,
)
actions = st.builds(
    Action,
    st.sampled_from(["move", "pickup", "putdown", "nil", "printText", "fly"]),
    st.lists(params, max_size=3).map(tuple),
)


@settings(max_examples=150, deadline=None)
@given(name=st.sampled_from(ENVS), seed=st.integers(0, 50), script=st.lists(actions, max_size=8))
def test_actions_never_escape_as_other_exceptions(name: str, seed: int, script: list) -> None:
    env = load_environment(name)()
    env.init({} if name == "printer" else {"seed": Numeral(seed), "blocks": Numeral(4)})
    env.start()
    env.register_agent("ag")
    env.associate_entity("ag", env.entities()[0])
    for action in script:
        try:
            env.perform_action("ag", action)
        except ActException:
            pass
        env.get_all_percepts("ag")


@settings(max_examples=150, deadline=None)
@given(
    name=st.sampled_from(ENVS),
    init=st.dictionaries(st.sampled_from(["state", "blocks", "seed", "robots", "x"]), params),
)
def test_init_parameters_never_escape_as_other_exceptions(name: str, init: dict) -> None:
    env = load_environment(name)()
    try:
        env.init(init)
    except EnvironmentInterfaceException:
        return
    env.register_agent("ag")
    env.associate_entity("ag", env.entities()[0])
    env.get_all_percepts("ag")
