"""The two private Prolog modules of one agent: made, loaded with the agent's knowledge and
beliefs, called and freed. The base every part of the mental state builds on.

Each agent owns two fresh Prolog modules (based on ``system`` only, so nothing from ``user``
or another agent leaks in): a belief module (knowledge + beliefs + percepts + messages) and a
goal module (knowledge again + the goal bases). The parts of
:class:`~goalagent.kb.mentalstate.MentalState` -- conditions, beliefs, goals, percepts and
mail, identity -- are subclasses of :class:`PrologModules`, joined into one object per agent,
so the agent calls ``state.insert`` and the cycle pays no delegation call. A part that keeps
state of its own sets it in its ``__init__`` before calling ``super().__init__``.
"""

from __future__ import annotations

import secrets
from collections.abc import Mapping, Sequence
from typing import Any

from goalagent import ast
from goalagent.kb.engine import Engine, KBError, get_engine
from goalagent.kb.limits import Limits
from goalagent.kb.terms import Atom, Struct, Term, Var
from goalagent.kb.watchdog import watchdog

__all__ = ["IMAGED", "PrologModules", "image_kept", "image_number", "instantiate", "note_image",
           "substitute", "text_of"]

TRUE, FALSE = Atom("true"), Atom("false")


def text_of(formula: ast.PrologText | str) -> str:
    """The Prolog text of a program fragment or plain string (anything else is a KBError)."""
    if isinstance(formula, ast.PrologText):
        return formula.text
    if isinstance(formula, str):
        return formula
    raise KBError(f"Prolog text expected, got {formula!r}")


def substitute(term: Term, bindings: Mapping[str, Term]) -> Term:
    """``term`` with every bound ``Var`` replaced by its value (lists are rebuilt)."""
    if isinstance(term, Var):
        return bindings.get(term.name, term) if term.name != "_" else term
    if isinstance(term, Struct):
        return Struct(term.name, tuple(substitute(arg, bindings) for arg in term.args))
    if isinstance(term, list):
        return [substitute(item, bindings) for item in term]
    return term


def instantiate(text: ast.PrologText | str, bindings: Mapping[str, Term],
                engine: Engine | None = None) -> Term:
    """The term written in ``text`` with ``bindings`` applied (unbound vars stay Var)."""
    return substitute((engine or get_engine()).parsed(text_of(text)), bindings)


_IMAGES: dict[tuple[object, ...], int] = {}
"""The numbers of the images kept so far (load_imaged/7 and declare_imaged/5 in
mentalstate_images.pl): what loading a program's knowledge and beliefs under the limits
that change how they load, or declaring formulas after such a load, did to an agent's
modules, which the next agent of the program does to its own without reading the texts."""
_MAX_IMAGES = 2000  # past it, agents load and declare from their texts
_KEPT: set[int] = set()  # the images Prolog keeps (it answered IMAGED)
IMAGED = Atom("imaged")  # what load_imaged/7 and declare_imaged/5 answer with an image


def image_kept(number: int | None) -> bool:
    """Whether Prolog keeps image ``number`` (None: no image)."""
    return number in _KEPT


def note_image(number: int, result: Term) -> None:
    """Notes that Prolog keeps image ``number`` when an imaged call answered IMAGED."""
    if result == IMAGED:
        _KEPT.add(number)


def image_number(key: tuple[object, ...]) -> int | None:
    """The number of the image of ``key`` (what was loaded or declared, and how); None
    past :data:`_MAX_IMAGES` images."""
    number = _IMAGES.get(key)
    if number is None and len(_IMAGES) < _MAX_IMAGES:
        number = _IMAGES[key] = len(_IMAGES)
    return number


class PrologModules:
    """One agent's belief and goal module, loaded with its knowledge and beliefs."""

    def __init__(self, agent_name: str, *, knowledge: Sequence[ast.PrologText] = (),
                 beliefs: Sequence[ast.PrologText] = (), engine: Engine | None = None,
                 limits: Limits | None = None) -> None:
        self._engine = engine or get_engine()
        self.agent_name = agent_name
        self.limits = limits or Limits()
        self._watchdog = watchdog()
        # Module names no agent can guess (another agent's are never named to it).
        secret = secrets.token_hex(8)
        self._b = Atom(f"ga_b_{secret}")
        self._g = Atom(f"ga_g_{secret}")
        # What the watchdog's memory watch needs of this agent's calls, and the memory
        # alarm it last accounted after (goalagent/kb/memory.py).
        self._memory = (str(self._b), self.limits.max_memory_bytes, agent_name)
        self._watchdog.note_budget(self.limits.max_memory_bytes)
        self._generation = self._watchdog.generation
        self._closed = False
        # What blind commitment (GoalBases) has still to do, which every part changes:
        # goals belief updates removed, not yet reported, and whether goals may have been
        # achieved unchecked (percepts, mail, a new goal base: Prolog's recheck flag as last
        # seen).
        self._achieved: list[list[Term]] = []
        self._recheck = True
        clauses = [("knowledge", text) for text in knowledge]
        clauses += [("beliefs", text) for text in beliefs]
        # Directives (op/3, use_module/1, ...) change how this agent reads text.
        self._directives = "\n".join(text_of(text) for _, text in clauses
                                     if text_of(text).lstrip().startswith(":-"))
        self._engine.call("new_agent", self._b, self._g)
        self._engine.call("set_limits", self._b, self.limits.max_inferences,
                          self.limits.max_beliefs, module="ga_guard")
        self._watchdog.time_limit = self.limits.max_query_seconds  # its directives run
        self._watchdog.running = self._memory
        if self._directives and self.limits.runs_code:  # (they may draw random numbers)
            self._engine.give_seed()
        sandbox = TRUE if self.limits.sandbox else FALSE
        runs_code = TRUE if self.limits.runs_code else FALSE
        # The image of this load (None: a program with directives loads from its texts):
        # the agents of a program loaded from one image hold the same in their modules.
        self._image = None if self._directives else image_number(
            ("load", tuple(clauses), self.limits.sandbox, self.limits.runs_code))
        image = self._image
        # (with its image kept, the texts are not even handed over)
        items = [] if image_kept(image) else [Struct(kind[0], (text_of(text),))
                                           for kind, text in clauses]
        if image is None:
            result = self._call("load", self._b, self._g, items, sandbox, runs_code, None)[5]
        else:
            result = self._call("load_imaged", image, self._b, self._g, items, sandbox,
                                runs_code, None)[6]
            note_image(image, result)
        if isinstance(result, Struct) and result.name == "error":
            index, message = result.args
            kind, text = clauses[int(index)]
            self.close()
            pos = text.pos if isinstance(text, ast.PrologText) else None
            where = f"{pos}: " if pos else ""
            raise KBError(f"{where}{kind} clause `{text_of(text)}`: {message}", pos)

    @property
    def engine(self) -> Engine:
        """The Prolog engine the state lives in."""
        return self._engine

    @property
    def belief_module(self) -> Atom:
        """The name of the belief module (rule clauses read texts with its operators)."""
        return self._b

    @property
    def modules(self) -> tuple[Atom, Atom]:
        """The names of the belief and the goal module."""
        return self._b, self._g

    @property
    def closed(self) -> bool:
        """Whether the modules were freed (:meth:`close`)."""
        return self._closed

    @property
    def directives(self) -> str:
        """The ``:-`` directives of knowledge and beliefs (they change how texts read)."""
        return self._directives

    def call(self, name: str, *args: Term | None) -> list[Any]:
        """Runs ga_kb:name(args) once (it must succeed): for goalagent.kb's own modules."""
        return self._call(name, *args)

    def _call(self, name: str, *args: Term | None) -> list[Any]:
        """Runs ga_kb:name(args) once (it must succeed); raises KBError when closed."""
        if self._closed:
            raise KBError(f"the mental state of {self.agent_name} is closed")
        result = self._engine.call(name, *args)
        if result is None:
            raise KBError(f"internal: ga_kb:{name}/{len(args)} failed")
        return result

    def _check_open(self) -> None:
        """Raises KBError when the state was closed (for calls that skip :meth:`_call`)."""
        if self._closed:
            raise KBError(f"the mental state of {self.agent_name} is closed")

    def _term(self, formula: ast.PrologText | str, bindings: Mapping[str, Term] | None) -> Term:
        """The formula as a term with the bindings applied (parsed once per text); without
        bindings it is the engine's shared cached term, so it is only handed to Prolog."""
        term = self._engine.parsed(text_of(formula))
        return substitute(term, bindings) if bindings else term

    def close(self) -> None:
        """Frees both Prolog modules; the object is unusable afterwards."""
        if self._closed:
            return
        if self._watchdog.running is self._memory:  # (no later query is this agent's)
            self._watchdog.running = None
        self._call("destroy", self._b, self._g)
        self._engine.forget_atom(self._b)
        self._engine.forget_atom(self._g)
        self._closed = True
