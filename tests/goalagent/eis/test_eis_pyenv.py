"""PythonEnvironment: actions from method signatures, parameter conversion and its errors."""

from __future__ import annotations

from collections.abc import Iterable

import pytest

from goalagent.eis import (
    ActException,
    ActExceptionKind,
    Action,
    ActionRefused,
    Function,
    Identifier,
    ManagementException,
    Numeral,
    ParameterList,
    PerceiveException,
    Percept,
    PerceptLike,
    PythonEnvironment,
    TruthValue,
    action,
)
from goalagent.kb.terms import Atom, Struct


class Store(PythonEnvironment):
    """A shelf of named items with actions covering every supported type hint."""

    name = "store"
    parameters = {"items": list, "limit": int, "open": bool, "note": object}

    def on_init(self, params: dict[str, object]) -> None:
        self.items: list[object] = list(params.get("items", []))  # type: ignore[arg-type]
        self.limit = params.get("limit", 3)
        self.open = params.get("open", True)
        self.calls: list[tuple] = []

    def percepts(self, entity: str) -> Iterable[PerceptLike]:
        return [
            ("count", len(self.items)),
            Percept.of("open", self.open),
            "ready",
            Struct("limit", (self.limit,)),
        ]

    @action("put")
    def put(self, entity: str, item: str) -> None:
        if len(self.items) >= self.limit:  # type: ignore[operator]
            raise ActionRefused(f"put({item}): the shelf is full")
        self.items.append(item)

    @action("typed")
    def typed(
        self, entity: str, n: int, x: float, flag: bool, names: list[str], term: Struct
    ) -> str:
        self.calls.append((n, x, flag, names, term))
        return "ok"

    @action("raw")
    def raw(self, entity: str, anything: object, param: Identifier, untyped=None) -> Percept:
        self.calls.append((anything, param, untyped))
        return Percept.of("got", param)

    @action("label")
    def label(self, entity: str, value: bool | int | str) -> None:
        self.calls.append((value,))

    @action("crash")
    def crash(self, entity: str) -> None:
        raise ZeroDivisionError("division by zero")


@pytest.fixture
def store() -> Store:
    """A running store with agent ``ag`` on its one entity."""
    environment = Store()
    environment.init({"items": ParameterList((Identifier("apple"),))})
    environment.start()
    environment.register_agent("ag")
    environment.associate_entity("ag", "entity")
    return environment


def act(env: PythonEnvironment, name: str, *values: object) -> dict[str, Percept | None]:
    return env.perform_action("ag", Action.of(name, *values))


def test_one_entity_by_default(store: Store) -> None:
    assert store.entities() == ["entity"]
    assert store.entity_type("entity") == "entity"
    assert Store.action_names() == ["crash", "label", "put", "raw", "typed"]


def test_percept_shorthands_are_converted(store: Store) -> None:
    assert [str(p) for p in store.get_all_percepts("ag")["entity"]] == [
        "count(1)",
        "open(true)",
        "ready",
        "limit(3)",
    ]


def test_parameters_are_converted_by_type_hints(store: Store) -> None:
    result = act(store, "typed", 3, 2, Identifier("true"), ["a", "b"], Function("f", ()))
    assert result == {"entity": Percept("ok")}
    assert store.calls == [(3, 2.0, True, ["a", "b"], Struct("f", ()))]
    assert isinstance(store.calls[0][1], float)
    act(store, "raw", Function("on", (Identifier("a"),)), "x", TruthValue(False))
    assert store.calls[1] == (Struct("on", (Atom("a"),)), Identifier("x"), False)


def test_union_hints_try_each_alternative_in_order(store: Store) -> None:
    act(store, "label", "false")
    act(store, "label", 4)
    act(store, "label", "x")
    assert store.calls == [(False,), (4,), ("x",)]
    with pytest.raises(ActException, match="must be true or false or an integer or a name or"):
        act(store, "label", 2.5)


def test_optional_parameters_may_be_left_out(store: Store) -> None:
    assert act(store, "raw", 1, "y") == {"entity": Percept.of("got", "y")}
    assert store.calls == [(1, Identifier("y"), None)]


@pytest.mark.parametrize(
    ("name", "values", "message"),
    [
        ("put", (), r"action put expects 1 parameter put\(item: a name or string\), got 0"),
        ("put", ("a", "b"), r"expects 1 parameter .*got 2 in put\(a,b\)"),
        ("raw", (1,), r"action raw expects 2 to 3 parameters .*got 1"),
        ("put", (3,), r"action put: parameter 1 \(item\) must be a name or string, got 3"),
        ("typed", (1.5, 1, True, [], Function("f", ())), r"parameter 1 \(n\) must be an integer"),
        ("typed", (1, "x", True, [], Function("f", ())), r"parameter 2 \(x\) must be a number"),
        ("typed", (1, 1, "yes", [], Function("f", ())), r"parameter 3 \(flag\) must be true or"),
        ("typed", (1, 1, True, [1], Function("f", ())), r"element a name or string, got .1. in"),
        ("typed", (1, 1, True, "ab", Function("f", ())), r"\(names\) must be a list, each"),
        ("typed", (1, 1, True, [], "f"), r"parameter 5 \(term\) must be a compound term"),
        ("raw", (1, 2), r"parameter 2 \(param\) must be an Identifier, got 2"),
    ],
)
def test_wrong_parameters_name_the_action_and_what_it_expects(
    store: Store, name: str, values: tuple, message: str
) -> None:
    with pytest.raises(ActException, match=message) as caught:
        act(store, name, *values)
    assert caught.value.kind is ActExceptionKind.WRONG_PARAMETERS
    assert store.calls == []


def test_unknown_action_lists_the_known_ones(store: Store) -> None:
    with pytest.raises(ActException, match=r"'fly' \(actions: crash, label, put, raw, typed\)"):
        act(store, "fly")


def test_refused_action_leaves_the_world_unchanged(store: Store) -> None:
    act(store, "put", "pear")
    act(store, "put", "plum")
    with pytest.raises(ActionRefused, match="the shelf is full") as caught:
        act(store, "put", "fig")
    assert caught.value.kind is ActExceptionKind.REFUSED
    assert store.items == ["apple", "pear", "plum"]


def test_crashing_action_becomes_a_failure_wrapping_the_error(store: Store) -> None:
    with pytest.raises(ActException, match="crash failed .*ZeroDivisionError") as caught:
        act(store, "crash")
    assert caught.value.kind is ActExceptionKind.FAILURE
    assert isinstance(caught.value.__cause__, ZeroDivisionError)
    assert act(store, "put", "pear") == {"entity": None}


def test_init_parameters_are_checked_and_converted() -> None:
    environment = Store()
    environment.init(
        {"limit": Numeral(5), "open": Identifier("false"), "note": Identifier("hi", string=True)}
    )
    assert (environment.limit, environment.open, environment.items) == (5, False, [])
    with pytest.raises(ManagementException, match=r"no init parameter 'limt' \(known: items"):
        Store().init({"limt": Numeral(1)})
    with pytest.raises(ManagementException, match="'limit' must be an integer, got many"):
        Store().init({"limit": Identifier("many")})


def test_undeclared_parameters_arrive_as_python_values() -> None:
    class Open(PythonEnvironment):
        name = "open"

        def on_init(self, params: dict[str, object]) -> None:
            self.got = params

    environment = Open()
    environment.init({"a": ParameterList((Numeral(1), TruthValue(True))), "b": Identifier("x")})
    assert environment.got == {"a": [1, True], "b": Atom("x")}


def test_errors_in_user_hooks_are_reported_not_leaked() -> None:
    class Broken(PythonEnvironment):
        name = "broken"

        def on_init(self, params: dict[str, object]) -> None:
            raise KeyError("gone")

        def percepts(self, entity: str) -> Iterable[PerceptLike]:
            return [3.5]  # type: ignore[list-item]

    environment = Broken()
    with pytest.raises(ManagementException, match="failed to initialise: KeyError"):
        environment.init({})
    assert environment.state.value == "initializing"

    class BadPercepts(PythonEnvironment):
        name = "bad"

        def percepts(self, entity: str) -> Iterable[PerceptLike]:
            return [3.5]  # type: ignore[list-item]

    bad = BadPercepts()
    bad.init({})
    bad.register_agent("a")
    bad.associate_entity("a", "entity")
    with pytest.raises(PerceiveException, match="produced 3.5, which is not a percept"):
        bad.get_all_percepts("a")


def test_reset_syncs_entities_with_the_new_parameters() -> None:
    class Many(PythonEnvironment):
        name = "many"
        parameters = {"n": int}

        def on_init(self, params: dict[str, object]) -> None:
            self.n = params.get("n", 1)

        def initial_entities(self) -> dict[str, str]:
            return {f"bot{i}": "bot" for i in range(self.n)}  # type: ignore[arg-type]

    environment = Many()
    environment.init({"n": Numeral(3)})
    assert environment.entities() == ["bot0", "bot1", "bot2"]
    environment.reset({"n": Numeral(2)})
    assert environment.entities() == ["bot0", "bot1"]


def test_class_definition_mistakes_are_caught_early() -> None:
    with pytest.raises(TypeError, match="unsupported type hint"):

        class BadHint(PythonEnvironment):
            @action("go")
            def go(self, entity: str, where: dict) -> None: ...

    with pytest.raises(TypeError, match="defined twice"):

        class Twice(PythonEnvironment):
            @action("go")
            def go(self, entity: str) -> None: ...

            @action("go")
            def go_again(self, entity: str) -> None: ...

    with pytest.raises(TypeError, match="needs \\(self, entity"):

        class NoEntity(PythonEnvironment):
            @action("go")
            def go(self) -> None: ...

    with pytest.raises(TypeError, match="must be plain positional"):

        class Star(PythonEnvironment):
            @action("go")
            def go(self, entity: str, *rest: str) -> None: ...


def test_subclasses_inherit_actions() -> None:
    class MoreStore(Store):
        @action("take")
        def take(self, entity: str) -> None:
            self.items.pop()

    assert MoreStore.action_names() == ["crash", "label", "put", "raw", "take", "typed"]
    assert Store.action_names() == ["crash", "label", "put", "raw", "typed"]


def test_init_accepts_python_shorthand_values() -> None:
    environment = Store()
    environment.init({"items": ["pear", "fig"], "limit": 4, "open": False})
    assert (environment.items, environment.limit, environment.open) == (["pear", "fig"], 4, False)
    with pytest.raises(ManagementException, match="init parameter 'note': cannot turn"):
        Store().init({"note": {"a": 1}})


def test_kill_ends_killed_even_when_the_hook_fails() -> None:
    class Sticky(PythonEnvironment):
        name = "sticky"

        def on_kill(self) -> None:
            raise OSError("device busy")

    environment = Sticky()
    environment.init({})
    with pytest.raises(ManagementException, match="failed to stop: OSError: device busy"):
        environment.kill()
    assert environment.state.value == "killed"


def test_pushed_percepts_accept_shorthand(store: Store) -> None:
    class Inbox:
        def __init__(self) -> None:
            self.got: list[str] = []

        def handle_percept(self, agent: str, percept: Percept) -> None:
            self.got.append(f"{agent}:{percept}")

    inbox = Inbox()
    store.register_agent("b")
    store.attach_agent_listener("ag", inbox)
    store.attach_agent_listener("b", inbox)
    store.push_percept(("delivered", "apple", 2), "entity")
    store.push_percept("closing")
    assert inbox.got == ["ag:delivered(apple,2)", "ag:closing", "b:closing"]
