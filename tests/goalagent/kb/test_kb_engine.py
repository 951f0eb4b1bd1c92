"""The SWI-Prolog engine: syntax checks by SWI's own reader, offsets, parsing, errors."""

from __future__ import annotations

import pytest

from goalagent.kb import (
    Atom,
    KBError,
    PrologRuntimeError,
    PrologSyntaxError,
    Struct,
    Var,
    get_engine,
)

engine = get_engine()


def test_one_engine_per_process() -> None:
    assert get_engine() is engine


@pytest.mark.parametrize(
    ("text", "names"),
    [
        ("a :- b, c", ()),
        ("X = 'quoted atom'", ("X",)),
        ('X = "str"', ("X",)),
        ("[H|T] = L", ("H", "T", "L")),
        ("(a ; b -> c)", ()),
        ("\\+ x", ()),
        ("X =.. L", ("X", "L")),
        ("X = 0'a", ("X",)),
        ("X = {a}", ("X",)),
        ("Y = f(X, _, _Z, X), Z is 1 + 2 * 3 ** 4 mod 5", ("Y", "X", "_Z", "Z")),
        ("on(X, Y), Y \\= table, tower([Y | T])", ("X", "Y", "T")),
        ("X = a % a comment at the end", ("X",)),
        ("X = /* inline */ a", ("X",)),
    ],
)
def test_check_query_returns_named_variables_in_order(text: str, names: tuple) -> None:
    assert engine.check_query(text) == names


def test_check_clause_accepts_rules_facts_directives_and_dcg() -> None:
    assert engine.check_clause("tower([X, Y | T]) :- on(X, Y), tower([Y | T])") == ("X", "Y", "T")
    assert engine.check_clause("block(a)") == ()
    assert engine.check_clause(":- dynamic on/2") == ()
    assert engine.check_clause("greeting --> [hello], name") == ()


@pytest.mark.parametrize(
    ("text", "offending"),
    [
        ("foo(a b)", "b"),
        ("f(a b c)", "b"),
        ("f(,)", ","),
        ("f(a,,b)", ","),
        ("foo)", ")"),
        ("   )", ")"),
        ("f(a) g", "g"),
        ("[a|b|c]", "|"),
        ("X == .", "."),
        ("a. b", "b"),
        ("X = 'abc", "'"),
        ('X = "abc', '"'),
    ],
)
def test_syntax_error_offset_points_at_the_offending_character(text: str, offending: str) -> None:
    with pytest.raises(PrologSyntaxError) as info:
        engine.check_query(text)
    assert text[info.value.offset] == offending
    assert info.value.message


@pytest.mark.parametrize("text", ["foo(", "f(a", "p :- ", "X = [a, b", ""])
def test_syntax_error_at_the_end_points_past_the_text(text: str) -> None:
    with pytest.raises(PrologSyntaxError) as info:
        engine.check_query(text)
    assert info.value.offset == len(text)


def test_error_offset_is_exact_for_a_known_case() -> None:
    with pytest.raises(PrologSyntaxError) as info:
        engine.check_clause("p(X) :- q(X) r(X)")
    assert info.value.offset == 13
    assert "Operator expected" in info.value.message


def test_a_clause_must_be_callable() -> None:
    with pytest.raises(PrologSyntaxError):
        engine.check_clause("3")
    with pytest.raises(PrologSyntaxError):
        engine.check_clause("X")
    assert engine.check_query("3") == ()


def test_non_text_is_a_clear_error() -> None:
    with pytest.raises(KBError, match="Prolog text expected"):
        engine.check_query(42)  # type: ignore[arg-type]


def test_parse_term_maps_every_kind_of_term() -> None:
    term = engine.parse_term(
        "f(X, _, 'a b', [1, 2.5 | T], \"str\", {a, b}, -3, 0'a, a-b, "
        "123456789012345678901234567890, X, 'it''s', [], '[]', g())"
    )
    assert term == Struct(
        "f",
        (
            Var("X"),
            Var("_"),
            Atom("a b"),
            Struct("[|]", (1, Struct("[|]", (2.5, Var("T"))))),
            "str",
            Struct("{}", (Struct(",", (Atom("a"), Atom("b"))),)),
            -3,
            97,
            Struct("-", (Atom("a"), Atom("b"))),
            123456789012345678901234567890,
            Var("X"),
            Atom("it's"),
            [],
            Atom("[]"),
            Struct("g", ()),
        ),
    )
    args = term.args
    assert isinstance(args[2], Atom) and not isinstance(args[4], Atom)
    assert isinstance(args[4], str)


def test_parse_term_results_are_fresh_copies() -> None:
    first = engine.parse_term("[a, b]")
    assert isinstance(first, list)
    first.append(Atom("c"))
    assert engine.parse_term("[a, b]") == [Atom("a"), Atom("b")]


def test_parse_term_rejects_bad_syntax() -> None:
    with pytest.raises(PrologSyntaxError):
        engine.parse_term("f(")


def test_format_writes_canonical_text_that_reads_back() -> None:
    term = Struct("on", (Atom("a b"), [1, -2.5, "s"]))
    assert engine.parse_term(engine.format(term)) == term


def test_runtime_errors_are_readable_and_the_engine_keeps_working() -> None:
    with pytest.raises(PrologRuntimeError) as info:
        engine.call("atom_length", 1, Atom("a"), module="system")
    assert "Type error" in info.value.message
    assert info.value.term is not None
    assert engine.call("atom_length", Atom("abc"), None, module="system") == [Atom("abc"), 3]


def test_failure_is_none_not_an_error() -> None:
    assert engine.call("atom_length", Atom("abc"), 4, module="system") is None


def test_unicode_atoms_and_strings_cross_the_seam() -> None:
    result = engine.call("atom_string", Atom("čaj ☕"), None, module="system")
    assert result == [Atom("čaj ☕"), "čaj ☕"]


def test_subclasses_tuples_and_bools_cross_as_the_term_they_stand_for() -> None:
    class Name(Atom):
        pass

    class Text(str):
        pass

    result = engine.call("=", [Name("a"), Text("b"), (1, 2.5), True, Struct("f", (False,))],
                         None, module="system")
    assert result[1] == [Atom("a"), "b", [1, 2.5], Atom("true"), Struct("f", (Atom("false"),))]
    assert [type(value) for value in result[1][:2]] == [Atom, str]


def test_unrepresentable_python_values_are_clear_errors() -> None:
    with pytest.raises(KBError, match="not a Prolog term"):
        engine.call("atom", object(), module="system")  # type: ignore[arg-type]


def test_text_prolog_cannot_hold_is_a_clear_error() -> None:
    with pytest.raises(KBError, match="cannot hold"):
        engine.call("atom", Atom("bad \udc80"), module="system")
    assert engine.call("atom", Atom("fine"), module="system") is not None


def test_write_shows_terms_like_prolog_write_and_writeq() -> None:
    term = Struct("-", (Atom("good"), 1))
    assert engine.write(term) == "good-1"
    assert engine.write([Atom("a b"), "s", Struct("f", (Atom("table"),))]) == "[a b,s,f(table)]"
    assert engine.write([Atom("a b"), "s"], quoted=True) == "['a b',\"s\"]"
    assert engine.write(Struct(",", (Atom("x"), Atom("y")))) == "x,y"


def test_seeding_makes_prolog_random_repeatable() -> None:
    def draws() -> list:
        result = engine.call("findall", Var("X"), Struct(",", (
            Struct("between", (1, 5, Var("_"))), Struct("random_between", (1, 10**9, Var("X"))))),
            None, module="system")
        assert result is not None
        return result[2]

    engine.seed_random(7)
    first = draws()
    engine.seed_random(7)
    assert draws() == first
    engine.seed_random(8)
    assert draws() != first


def test_a_final_full_stop_is_pointed_at() -> None:
    with pytest.raises(PrologSyntaxError) as info:
        engine.check_clause("foo(X) :- X > 0.  ")
    assert info.value.offset == 15
    assert "final '.'" in info.value.message
