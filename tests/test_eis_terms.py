"""EIS terms: conversions to and from kb terms, and round trips through real SWI-Prolog.

The Prolog oracle reads the text ``format_term`` writes and describes the term it read (type,
exact name as code points, exact number), so a term that Prolog reads differently from what
the EIS parameter means fails the test.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from pyswip import Prolog

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
from goalagent.kb.terms import Atom, Struct, Var, format_term

DESCRIBE = r"""
eis_desc(T, "v") :- var(T), !.
eis_desc(T, D) :- T == [], !, D = "l()".
eis_desc(T, D) :- is_list(T), !, maplist(eis_desc, T, Ds),
    atomic_list_concat(Ds, ',', J), format(string(D), "l(~w)", [J]).
eis_desc(T, D) :- atom(T), !, eis_codes(T, H), format(string(D), "a(~w)", [H]).
eis_desc(T, D) :- string(T), !, eis_codes(T, H), format(string(D), "s(~w)", [H]).
eis_desc(T, D) :- integer(T), !, format(string(D), "i(~d)", [T]).
eis_desc(T, D) :- float(T), !, format(string(D), "f(~17e)", [T]).
eis_desc(T, D) :- compound(T), !, compound_name_arguments(T, N, As), eis_codes(N, H),
    maplist(eis_desc, As, Ds), atomic_list_concat(Ds, ',', J),
    format(string(D), "c(~w;~w)", [H, J]).
eis_codes(X, H) :- atom_codes(X, Cs), atomic_list_concat(Cs, '-', H).
eis_read(Codes, Desc) :- string_codes(S, Codes), term_string(T, S), eis_desc(T, D),
    atom_string(Desc, D).
"""


@pytest.fixture(scope="module")
def prolog(tmp_path_factory: pytest.TempPathFactory) -> Prolog:
    """The real SWI-Prolog engine with the term describer loaded."""
    engine = Prolog()
    list(engine.query("set_prolog_flag(debug_on_error, false)"))
    path: Path = tmp_path_factory.mktemp("eis") / "eis_desc.pl"
    path.write_text(DESCRIBE)
    list(engine.query(f"consult('{path}')"))
    return engine


def prolog_describe(engine: Prolog, text: str) -> str:
    """How SWI-Prolog reads ``text``: the describer's one-line account of the term."""
    codes = "[" + ",".join(str(ord(c)) for c in text) + "]"
    answers = list(engine.query(f"eis_read({codes}, D)", catcherrors=True))
    assert len(answers) == 1, f"Prolog could not read {text!r}"
    return str(answers[0]["D"])


def codes(name: str) -> str:
    return "-".join(str(ord(c)) for c in name)


def describe(param: Parameter) -> str:
    """What the EIS parameter means, in the describer's notation."""
    if isinstance(param, Identifier):
        return f"{'s' if param.string else 'a'}({codes(param.value)})"
    if isinstance(param, TruthValue):
        return f"a({codes('true' if param.value else 'false')})"
    if isinstance(param, Numeral):
        if isinstance(param.value, int):
            return f"i({param.value})"
        return f"f({param.value:.17e})"
    if isinstance(param, ParameterList):
        return "l(" + ",".join(describe(item) for item in param.params) + ")"
    assert isinstance(param, Function)
    return f"c({codes(param.name)};" + ",".join(describe(item) for item in param.params) + ")"


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
def test_parameter_round_trips_through_kb_terms(param: Parameter) -> None:
    assert from_term(to_term(param)) == param


@QUICK
@given(param=parameters)
def test_prolog_reads_the_written_term_as_the_parameter(prolog: Prolog, param: Parameter) -> None:
    text = format_term(to_term(param))
    assert prolog_describe(prolog, text) == describe(param)


@QUICK
@given(name=names, params=st.lists(parameters, max_size=3).map(tuple))
def test_percepts_and_actions_round_trip(prolog: Prolog, name: str, params: tuple) -> None:
    percept = Percept(name, params)
    action = Action(name, params)
    assert percept_from_term(percept_to_term(percept)) == percept
    assert action_from_term(action_to_term(action)) == action
    expected = describe(Function(name, params)) if params else describe(Identifier(name))
    assert prolog_describe(prolog, str(percept)) == expected
    assert prolog_describe(prolog, str(action)) == expected


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
def test_known_texts(prolog: Prolog, param: Parameter, text: str) -> None:
    assert format_term(to_term(param)) == text
    assert prolog_describe(prolog, text) == describe(param)


def test_identifier_maps_to_atom_and_string_flag_to_prolog_string() -> None:
    assert to_term(Identifier("a")) == Atom("a")
    assert isinstance(to_term(Identifier("a")), Atom)
    string_term = to_term(Identifier("a", string=True))
    assert string_term == "a" and not isinstance(string_term, Atom)
    assert from_term("hello") == Identifier("hello", string=True)
    assert from_term(Atom("hello")) == Identifier("hello")


def test_numerals_keep_int_and_float_apart() -> None:
    assert Numeral(1) != Numeral(1.0)
    assert len({Numeral(1), Numeral(1.0)}) == 2
    assert Numeral(math.nan) == Numeral(math.nan)
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
