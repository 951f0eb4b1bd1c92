"""What the simulated environments share: Java's Random, EIS2Java's percept filters, rounds,
lenient init parameters, atomic PNG snapshots, and environment jar names."""

from __future__ import annotations

import pytest

from goalagent.eis import ManagementException, load_environment
from goalagent.eis.envs.filters import Filter, PerceptFilter
from goalagent.eis.envs.javarandom import JavaRandom, _java_string_hash, java_hashmap_order
from goalagent.eis.envs.support import (
    RoundClock,
    SnapshotWriter,
    bool_param,
    check_known,
    float_param,
    int_param,
)
from goalagent.eis.registry import _jar_name
from goalagent.kb.terms import Atom
from goalagent.mas import parse_parameter


def test_java_random_gives_javas_numbers() -> None:
    # Values printed by java.util.Random (documented widely, e.g. new Random(42).nextInt()).
    assert JavaRandom(42).next_int() == -1170105035
    assert JavaRandom(0).next_int() == -1155484576
    assert JavaRandom(42).next_double() == 0.7275636800328681
    assert JavaRandom(0).next_gaussian() == 0.8025330637390305
    assert JavaRandom(42).next_int_below(10) == 0


def test_java_random_bounded_ints_stay_in_range_and_repeat_per_seed() -> None:
    first = [JavaRandom(7).next_int_below(6) for _ in range(3)]
    draws = JavaRandom(7)
    values = [draws.next_int_below(6) for _ in range(1000)]
    assert set(values) == set(range(6))
    again = JavaRandom(7)
    assert [again.next_int_below(6) for _ in range(1000)] == values
    assert first == [values[0]] * 3
    power_of_two = JavaRandom(3)
    assert all(0 <= power_of_two.next_int_below(8) < 8 for _ in range(100))
    with pytest.raises(ValueError):
        JavaRandom(1).next_int_below(0)


def test_java_string_hash_and_hashmap_order() -> None:
    assert _java_string_hash("abc") == 96354  # "abc".hashCode()
    assert _java_string_hash("Aa") == _java_string_hash("BB") == 2112
    # Buckets of a 16-slot table: a (97 & 15 = 1), q (113 & 15 = 1), b (98 & 15 = 2).
    assert java_hashmap_order(["b", "a", "q"]) == ["a", "q", "b"]  # q: 113 & 15 = 1
    # Same bucket: insertion order.
    assert java_hashmap_order(["BB", "Aa"]) == ["BB", "Aa"]
    many = [f"Room{i}" for i in range(20)]  # more than 12 keys: a 32-slot table
    assert sorted(java_hashmap_order(many)) == sorted(many)


def test_filters_as_eis_0_7() -> None:
    f = PerceptFilter()
    assert f.apply("e", "p", Filter.ALWAYS, [1]) == ([1], [])
    assert f.apply("e", "p", Filter.ALWAYS, [1]) == ([1], [])
    assert f.apply("e", "o", Filter.ONCE, [1, 2]) == ([1, 2], [])
    assert f.apply("e", "o", Filter.ONCE, [1, 2]) == ([], [])
    assert f.sent_once("e", "o") and not f.sent_once("other", "o")
    assert f.apply("e", "c", Filter.ON_CHANGE, [1, 2]) == ([1, 2], [])
    assert f.apply("e", "c", Filter.ON_CHANGE, [1, 2]) == ([], [])
    assert f.apply("e", "c", Filter.ON_CHANGE, [1, 3]) == ([3], [])  # only the new
    assert f.apply("other", "c", Filter.ON_CHANGE, [1]) == ([1], [])  # per entity
    with pytest.raises(ValueError, match="legacy"):
        f.apply("e", "n", Filter.ON_CHANGE_NEG, [1])
    f.reset("e")
    assert f.apply("e", "o", Filter.ONCE, [1]) == ([1], [])


def test_filters_as_eis_0_5() -> None:
    f = PerceptFilter(legacy=True)
    assert f.apply("e", "c", Filter.ON_CHANGE, [1, 2]) == ([1, 2], [])
    assert f.apply("e", "c", Filter.ON_CHANGE, [1, 3]) == ([1, 3], [])  # all again
    assert f.apply("e", "n", Filter.ON_CHANGE_NEG, [(1,), (2,)]) == ([(1,), (2,)], [])
    assert f.apply("e", "n", Filter.ON_CHANGE_NEG, [(1,), (2,)]) == ([], [])
    changed = f.percepts("e", "n", Filter.ON_CHANGE_NEG, [(2,), (4, "x")])
    assert [str(p) for p in changed] == ["n(4,x)", "not(n(1))"]


def test_rounds_end_when_an_entity_perceives_again() -> None:
    clock = RoundClock()
    assert [clock.perceive(e) for e in ["a", "b", "c", "a", "b", "c", "a"]] == [
        False, False, False, True, False, False, True]
    assert clock.rounds == 2
    assert clock.perceive("a") and clock.rounds == 3  # alone: every cycle is a round


def test_lenient_parameters() -> None:
    params = {"n": "3", "m": 4, "f": "0.5", "g": 2, "yes": "true", "no": Atom("false"),
              "bad": "x", "real": 2.0}
    assert int_param("env", params, "n", 0) == 3
    assert int_param("env", params, "m", 0) == 4
    assert int_param("env", params, "real", 0) == 2
    assert int_param("env", params, "missing", 9) == 9
    assert float_param("env", params, "f", 0.0) == 0.5
    assert float_param("env", params, "g", 0.0) == 2.0
    assert bool_param("env", params, "yes", False) is True
    assert bool_param("env", params, "no", True) is False
    with pytest.raises(ManagementException, match="'bad' must be a whole number"):
        int_param("env", params, "bad", 0)
    with pytest.raises(ManagementException, match="'m' must be in 5..inf"):
        int_param("env", params, "m", 0, minimum=5)
    with pytest.raises(ManagementException, match="'bad' must be true or false"):
        bool_param("env", params, "bad", False)
    with pytest.raises(ManagementException, match="'bad' must be a number"):
        float_param("env", params, "bad", 0.0)
    with pytest.raises(ManagementException, match="no init parameter 'bad' .known: n, m"):
        check_known("env", {"n": 1, "bad": 2}, {"n": "", "m": ""})


def test_snapshots_are_written_whole(tmp_path) -> None:
    writer = SnapshotWriter(tmp_path / "shots", "demo")

    def draw(figure) -> None:
        figure.add_subplot(1, 1, 1).plot([0, 1], [1, 0])

    path = writer.write(3, draw)
    assert path.name == "demo-000003.png"
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert [p.name for p in path.parent.iterdir()] == [path.name]  # no temp file left
    (tmp_path / "file").write_text("x")
    with pytest.raises(ManagementException, match="cannot create snapshot directory"):
        SnapshotWriter(tmp_path / "file" / "sub", "demo")


@pytest.mark.parametrize(
    ("jar", "name"),
    [
        ("bw4t-client-3.10.1.jar", "bw4t"),
        ("bw4t-client-3.9.3.jar", "bw4t"),
        ("bw4t-client-3.8.5.jar", "bw4t-3.8"),
        ("bw4t-client-3.8.5-jar-with-dependencies.jar", "bw4t-3.8"),
        ("bw4t-client-3.8.0.jar", "bw4t-2"),
        ("../lib/bw4t-client-3.8.3-jar-with-dependencies.jar", "bw4t-2"),
        ("BW4T2/BW4TClient.jar", "bw4t-2"),
        ("BW4T2\\BW4TClient.jar", "bw4t-2"),
        ("ElevatorSim-1.3.2.jar", "elevator"),
        ("elevatorenv.jar", "elevator"),
        ("hanoi-1.0.0.jar", "hanoi"),
        ("vacuumworld-1.2.0.jar", None),
    ],
)
def test_environment_jar_names(jar: str, name: str | None) -> None:
    assert _jar_name(jar) == name
    if name is not None:
        assert load_environment(jar) is load_environment(name)


def test_capitalised_env_param_is_a_name_not_a_variable() -> None:
    assert parse_parameter("TwoRooms") == Atom("TwoRooms")
    assert parse_parameter("'x y'") == Atom("x y")
    assert parse_parameter("[0,1]") == [0, 1]
