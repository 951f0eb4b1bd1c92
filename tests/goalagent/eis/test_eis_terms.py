"""EIS terms: conversions to and from kb terms, and round trips through real SWI-Prolog.

The round trip writes a parameter as Prolog text (``format_term``), has SWI-Prolog read it
(``Engine.parse_term``: SWI's own reader, results as type-exact kb terms) and converts it back;
an atom read as a string, a float read as an integer or a name read differently fails the test.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from goalagent.eis import (
    Action,
    Function,
    Identifier,
    Numeral,
    Parameter,
    ParameterList,
    Percept,
    TranslationException,
    TruthValue,
    action_from_term,
    action_to_term,
    from_term,
    percept_from_term,
    percept_to_term,
    to_parameter,
    to_python,
    to_term,
)
from goalagent.kb.engine import get_engine
from goalagent.kb.terms import Atom, Struct, Var, format_term

pytestmark = pytest.mark.heavy  # run first (tests/conftest.py)


def through_prolog(text: str) -> Parameter:
    """The EIS parameter for the term SWI-Prolog reads from ``text``."""
    return from_term(get_engine().parse_term(text))


# Names: printable ASCII (letters, digits, symbol chars, quotes, backslash), a few non-ASCII
# letters, space, newline and tab. "[]" is excluded: SWI-Prolog 7 reads it as the empty list.
NAME_CHARS = st.sampled_from(
    [chr(c) for c in range(32, 127)] + ["é", "ß", "λ", "中", "\n", "\t"]
)
names = st.text(NAME_CHARS, max_size=8).filter(lambda name: name != "[]")
identifiers = st.builds(Identifier, names, st.booleans())
numerals = st.builds(
    Numeral,
    st.one_of(
        st.integers(min_value=-(2**70), max_value=2**70),
        st.floats(allow_nan=False),
    ),
)
parameters = st.recursive(
    st.one_of(identifiers, numerals),
    lambda inner: st.one_of(
        st.builds(ParameterList, st.lists(inner, max_size=4).map(tuple)),
        st.builds(Function, names, st.lists(inner, max_size=3).map(tuple)),
    ),
    max_leaves=12,
)

QUICK = settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@QUICK
@given(parameters)
def test_parameter_round_trips_through_kb_terms_and_prolog_s_reader(param: Parameter) -> None:
    # one drawn parameter for both trips: drawing it is most of what an example costs
    assert from_term(to_term(param)) == param
    assert through_prolog(format_term(to_term(param))) == param


@QUICK
@given(name=names, params=st.lists(parameters, max_size=3).map(tuple))
def test_percepts_and_actions_round_trip(name: str, params: tuple) -> None:
    percept = Percept(name, params)
    action = Action(name, params)
    assert percept_from_term(percept_to_term(percept)) == percept
    assert action_from_term(action_to_term(action)) == action
    assert percept_from_term(get_engine().parse_term(str(percept))) == percept
    assert action_from_term(get_engine().parse_term(str(action))) == action


@pytest.mark.parametrize(
    ("param", "text"),
    [
        (Identifier("Hello world"), "'Hello world'"),
        (Identifier("it's"), "'it\\'s'"),
        (Identifier("it's", string=True), '"it\'s"'),
        (Identifier("X"), "'X'"),
        (Numeral(-3), "-3"),
        (Numeral(-2.5), "-2.5"),
        (Numeral(1.0), "1.0"),
        (TruthValue(True), "true"),
        (ParameterList((ParameterList(()), ParameterList((Numeral(1),)))), "[[],[1]]"),
        (Function("on", (Identifier("a"), Identifier("table"))), "on(a,table)"),
    ],
)
def test_known_texts(param: Parameter, text: str) -> None:
    assert format_term(to_term(param)) == text
    expected = Identifier("true") if isinstance(param, TruthValue) else param
    assert through_prolog(text) == expected


def test_prolog_spellings_of_the_same_atom_read_alike() -> None:
    assert through_prolog("'it''s'") == Identifier("it's")
    assert through_prolog("'abc'") == Identifier("abc")
    assert through_prolog("\"tab\\there\"") == Identifier("tab\there", string=True)
    assert through_prolog("f( -1 , [ a | [ b ] ] )") == Function(
        "f", (Numeral(-1), ParameterList((Identifier("a"), Identifier("b"))))
    )
    assert through_prolog("- 1") == Function("-", (Numeral(1),))  # standard: not a numeral


def test_identifier_maps_to_atom_and_string_flag_to_prolog_string() -> None:
    assert to_term(Identifier("a")) == Atom("a")
    assert isinstance(to_term(Identifier("a")), Atom)
    string_term = to_term(Identifier("a", string=True))
    assert string_term == "a" and not isinstance(string_term, Atom)
    assert from_term("hello") == Identifier("hello", string=True)
    assert from_term(Atom("hello")) == Identifier("hello")


def test_numerals_compare_exactly() -> None:
    assert Numeral(1) != Numeral(1.0)
    assert Numeral(0.0) != Numeral(-0.0)
    assert len({Numeral(1), Numeral(1.0)}) == 2
    assert Numeral(math.nan) == Numeral(math.nan)
    assert through_prolog("-0.0") == Numeral(-0.0)
    assert through_prolog("1.0Inf") == Numeral(math.inf)
    assert from_term(2) == Numeral(2) and from_term(2.0) == Numeral(2.0)


def test_truth_values_write_as_atoms_and_read_back_as_identifiers() -> None:
    assert to_term(TruthValue(False)) == Atom("false")
    assert from_term(to_term(TruthValue(True))) == Identifier("true")


def test_variables_are_refused_with_a_clear_message() -> None:
    with pytest.raises(TranslationException, match="unbound variable X"):
        from_term(Struct("on", (Var("X"), Atom("b"))))
    with pytest.raises(TranslationException, match="an action is an unbound variable"):
        action_from_term(Var("A"))
    with pytest.raises(TranslationException, match="atom or a compound term, got 3"):
        percept_from_term(3)


def test_zero_argument_compound_is_a_percept_without_parameters() -> None:
    assert percept_from_term(Struct("tick", ())) == Percept("tick")
    assert percept_to_term(Percept("tick")) == Atom("tick")


def test_python_shorthand_values() -> None:
    assert Percept.of("on", "a", "table") == Percept(
        "on", (Identifier("a"), Identifier("table"))
    )
    assert to_parameter((1, 2.5, True, [])) == ParameterList(
        (Numeral(1), Numeral(2.5), TruthValue(True), ParameterList(()))
    )
    assert to_parameter(Struct("f", ("s",))) == Function("f", (Identifier("s", string=True),))
    with pytest.raises(TranslationException, match="cannot turn"):
        to_parameter({"a": 1})
    assert to_python(Function("f", (TruthValue(True), Identifier("x")))) == Struct(
        "f", (True, Atom("x"))
    )


def test_parameters_must_be_parameters() -> None:
    with pytest.raises(TypeError, match="to_parameter"):
        Percept("on", ("a", "b"))  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        Numeral(True)
    with pytest.raises(TypeError):
        Identifier(3)  # type: ignore[arg-type]


# A percept keeps the term it came from (one conversion; issue 25): checked against what the
# parameters say, for any parameters, shorthand values and truth values.
values = st.recursive(
    st.one_of(names, st.booleans(), st.integers(), st.floats(allow_nan=False), parameters),
    lambda inner: st.one_of(st.lists(inner, max_size=3), st.lists(inner, max_size=3).map(tuple)),
    max_leaves=8,
)


def has_list(param: Parameter) -> bool:
    if isinstance(param, ParameterList):
        return True
    return isinstance(param, Function) and any(has_list(item) for item in param.params)


def expected_term(name: str, params: tuple[Parameter, ...]) -> object:
    return Struct(name, tuple(to_term(p) for p in params)) if params else Atom(name)


@QUICK
@given(name=names, shorthand=st.lists(values, max_size=3))
def test_a_percept_of_shorthand_is_its_parameters_and_their_term(name: str,
                                                                  shorthand: list) -> None:
    params = tuple(to_parameter(value) for value in shorthand)
    percept = Percept.of(name, *shorthand)
    assert percept == Percept(name, params) and percept.params == params
    assert percept_to_term(percept) == expected_term(name, params)
    assert hash(percept) == hash(Percept(name, params))


@QUICK
@given(name=names.filter(bool), params=st.lists(parameters, min_size=1, max_size=3).map(tuple))
def test_a_percept_from_a_term_hands_on_that_very_term(name: str, params: tuple) -> None:
    term = Struct(name, tuple(to_term(p) for p in params))
    percept = percept_from_term(term)
    if any(has_list(param) for param in params):  # copied: the environment may change its own
        assert percept_to_term(percept) == term
    else:
        assert percept_to_term(percept) is term  # not rebuilt
    assert percept.params == params and percept == Percept(name, params)


def test_a_percept_term_is_made_canonical_once_and_bad_ones_are_refused() -> None:
    tuples = percept_from_term(Struct("at", (Atom("a"), (1, 2))))
    assert percept_to_term(tuples) == Struct("at", (Atom("a"), [1, 2]))
    truth = percept_from_term(Struct("open", (True,)))  # a bool stays a truth value
    assert truth.params == (TruthValue(True),)
    assert percept_to_term(truth) == Struct("open", (Atom("true"),))
    with pytest.raises(TranslationException, match="unbound variable X"):
        percept_from_term(Struct("at", (Atom("a"), [Var("X")])))
    with pytest.raises(TranslationException, match="cannot turn None"):
        Percept.of("at", [1, None])


def test_percepts_and_actions_are_values() -> None:
    import pickle
    from dataclasses import FrozenInstanceError

    percept = percept_from_term(Struct("on", (Atom("a"), Atom("b"))))
    with pytest.raises(FrozenInstanceError):
        percept.name = "off"  # type: ignore[misc]
    assert pickle.loads(pickle.dumps(percept)) == percept
    assert repr(percept) == ("Percept(name='on', params=(Identifier(value='a', string=False), "
                             "Identifier(value='b', string=False)))")
    assert percept != Action("on", percept.params) and str(percept) == "on(a,b)"
