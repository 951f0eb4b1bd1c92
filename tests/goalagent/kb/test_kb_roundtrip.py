"""Terms survive Python -> SWI-Prolog -> Python unchanged (property tests, real SWI-Prolog)."""

from __future__ import annotations

import math

from hypothesis import given, settings
from hypothesis import strategies as st

from goalagent import ast
from goalagent.kb import Atom, MentalState, Struct, Term, Var, format_term, get_engine

engine = get_engine()

_text = st.text(st.characters(blacklist_categories=("Cs",)), max_size=12)
atoms = st.one_of(
    st.sampled_from(["a", "it's", "a b", "[]", "{}", "-", "Hello", "\\", "", "é☕", ",", "|"]),
    _text,
).map(Atom)
strings = _text
integers = st.one_of(st.integers(-(2**70), 2**70), st.integers(-5, 5))
floats = st.floats(allow_nan=False, width=64)
leaves = st.one_of(atoms, strings, integers, floats)
names = st.one_of(st.sampled_from(["f", "-", "{}", ":-", "'q'", "a b", ","]), _text).filter(
    lambda name: name != "[|]"
)


def _extend(children: st.SearchStrategy[Term]) -> st.SearchStrategy[Term]:
    structs = st.builds(
        lambda name, args: Struct(name, tuple(args)), names, st.lists(children, max_size=3)
    )
    return st.one_of(st.lists(children, max_size=4), structs)


terms = st.recursive(leaves, _extend, max_leaves=12)


def same(left: Term, right: Term) -> bool:
    """Equal as Prolog terms: same types (atom vs string, int vs float), -0.0 kept."""
    if type(left) is not type(right):
        return False
    if isinstance(left, float):
        return left == right and math.copysign(1, left) == math.copysign(1, right)
    if isinstance(left, list):
        return len(left) == len(right) and all(map(same, left, right))
    if isinstance(left, Struct):
        return (left.name == right.name and len(left.args) == len(right.args)
                and all(map(same, left.args, right.args)))
    return left == right


@settings(max_examples=150, deadline=None)
@given(terms)
def test_python_prolog_python_round_trip(term: Term) -> None:
    result = engine.call("=", term, None, module="system", read=(0, 1))
    assert result is not None
    assert same(result[0], term) and same(result[1], term)


@settings(max_examples=150, deadline=None)
@given(terms)
def test_prolog_checks_term_identity(term: Term) -> None:
    assert engine.call("==", term, term, module="system") is not None
    assert engine.call("ground", term, module="system") is not None


@settings(max_examples=100, deadline=None)
@given(terms.filter(lambda t: "[]" not in format_term(t)))
def test_formatted_text_reads_back_as_the_same_term(term: Term) -> None:
    assert same(engine.parse_term(format_term(term)), term)


@settings(max_examples=60, deadline=None)
@given(st.lists(terms, min_size=1, max_size=4))
def test_terms_survive_a_belief_round_trip(args: list[Term]) -> None:
    with MentalState("roundtrip") as state:
        fact = Struct("fact", tuple(args))
        head = "fact(" + ",".join(f"A{i}" for i in range(len(args))) + ")"
        bindings = {f"A{i}": arg for i, arg in enumerate(args)}
        changes = state.insert(head, bindings)
        assert len(changes) == 1 and changes[0][0] == "+" and same(changes[0][1], fact)
        assert len(state.beliefs()) == 1 and same(state.beliefs()[0], fact)
        answers = state.query("bel", head)
        assert len(answers) == 1
        assert all(same(answers[0][f"A{i}"], arg) for i, arg in enumerate(args))
        assert state.query("bel", head, bindings) == [bindings]


def test_variables_keep_their_identity_in_answers() -> None:
    result = engine.call("=", Struct("f", (Var("X"), Var("Y"), Var("X"))), None, module="system")
    assert result is not None
    value = result[1]
    assert isinstance(value, Struct)
    first, second, third = value.args
    assert isinstance(first, Var) and isinstance(second, Var)
    assert first == third and first != second


def test_partial_lists_come_back_as_cons_cells() -> None:
    with MentalState("partial") as state:
        term = state.instantiate(ast.PrologText("[a, b | T]", ast.Pos("x", 1, 1)), {})
        assert term == Struct("[|]", (Atom("a"), Struct("[|]", (Atom("b"), Var("T")))))
        closed = state.instantiate("[a, b | T]", {"T": [Atom("c")]})
        result = engine.call("=", closed, None, module="system")
        assert result is not None and result[1] == [Atom("a"), Atom("b"), Atom("c")]
