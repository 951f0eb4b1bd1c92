"""Calling Prolog from Python and Python from Prolog, over the C foreign interface: the
engine's base (engine.py adds start-up, syntax checks, parsing and writing).

Every query is opened, drained or cut, and closed inside one Python call, with exceptions
caught (``Q_CATCH``), so Prolog never enters the tracer; a Prolog exception becomes a
``PrologRuntimeError`` with SWI's message, a Python exception raised inside a foreign
predicate is raised again where Python called Prolog. Each query is a stretch in Prolog
that the watchdog (goalagent.kb.watchdog) bounds.
"""

from __future__ import annotations

import ctypes
from collections.abc import Callable, Sequence
from ctypes import c_size_t, c_void_p
from threading import get_ident
from time import monotonic

from goalagent.kb.clib import (
    INT_BUF,
    INT_REF,
    Q_CATCH,
    Q_PASS,
    TEXT_FLAGS,
    PL_call_predicate,
    PL_clear_exception,
    PL_cut_query,
    PL_discard_foreign_frame,
    PL_erase,
    PL_exception,
    PL_get_int64,
    PL_is_acyclic,
    PL_new_term_ref,
    PL_new_term_refs,
    PL_next_solution,
    PL_open_foreign_frame,
    PL_open_query,
    PL_predicate,
    PL_put_atom,
    PL_put_term,
    PL_raise_exception,
    PL_record,
    PL_recorded,
    PL_register_foreign_in_module,
    PL_thread_attach_engine,
    PL_thread_self,
    PL_unify,
    PL_unregister_atom,
    term_t,
    text_of,
)
from goalagent.kb.conversion import Record, TermConversion
from goalagent.kb.errors import KBError, PrologRuntimeError
from goalagent.kb.stretches import Stretches
from goalagent.kb.terms import Struct, Term, Var, format_term

__all__ = ["PrologCalls", "define_foreign"]

_PYTHON_ERROR = "$ga_python"  # the Prolog exception that carries a Python one out of Prolog
_INFERENCES_SPENT = "inference_limit_exceeded"  # call_with_inference_limit/3's exception

# A foreign predicate of arity 2 as SWI calls it: foreign_t f(term_t a1, term_t a2).
_FOREIGN_2 = ctypes.CFUNCTYPE(c_size_t, term_t, term_t)


class PrologCalls(TermConversion, Stretches):
    """Queries and their errors, on the thread that runs Prolog (each query a stretch: see
    :class:`~goalagent.kb.stretches.Stretches`)."""

    def __init__(self) -> None:
        TermConversion.__init__(self)
        Stretches.__init__(self)
        self._thread = get_ident()
        if PL_thread_self() == -1:  # made in another thread than SWI's first one
            self._attach_thread()
        self._preds: dict[tuple[str, int, str], int] = {}
        # Two term references outside any frame, for the outputs of call_once's plans (made
        # once: a term reference each cycle is a C call); they belong to this thread.
        self._outputs = PL_new_term_refs(2)
        self._outputs_thread = self._thread
        self._foreign: list[object] = []  # ctypes callbacks SWI holds: keep them alive
        self._python_errors: list[BaseException] = []  # raised inside foreign predicates
        # A seed for Prolog's random generator not given to it yet (see seed_random):
        # given before the next call of a predicate not in _seedless, the predicates that
        # run no agent code (so draw no random number).
        self.pending_seed: int | None = None
        self._seedless: set[int] = set()

    def predicate(self, name: str, arity: int, module: str) -> int:
        """A predicate handle for ``module:name/arity`` (cached: the runtime's own modules
        only, never an agent's, whose handles would die with it)."""
        key = (name, arity, module)
        handle = self._preds.get(key)
        if handle is None:
            if get_ident() != self._thread:  # SWI needs an engine in this thread
                self._attach_thread()
            handle = PL_predicate(name.encode(), arity, module.encode())
            self._preds[key] = handle
        return handle

    def own_predicate(self, name: str, arity: int, module: str) -> int:
        """A predicate handle for ``module:name/arity`` in an agent's module (not cached:
        it dies with the agent)."""
        if get_ident() != self._thread:
            self._attach_thread()
        return PL_predicate(name.encode(), arity, module.encode())

    def forget_atom(self, name: str) -> None:
        """Drops ``name`` from the atom cache (e.g. a destroyed module) so Prolog can GC it."""
        handle = self._atoms.pop(name, None)
        if handle is not None:
            self._atom_names.pop(handle, None)
            PL_unregister_atom(handle)

    def call(self, name: str, *args: Term | None, module: str = "ga_kb", marks: bool = False,
             read: Sequence[int] | None = None) -> list[Term | None] | None:
        """Runs ``module:name(args)`` once; ``None`` args are fresh variables. Returns the
        arguments after the first solution (only the ``None`` ones, or those listed in
        ``read``, are read back from Prolog; the others are returned as given), or ``None``
        when the goal fails."""
        if read is None:
            read = [i for i, arg in enumerate(args) if arg is None]
        answers = self.solve(self.predicate(name, len(args), module), len(args),
                             list(enumerate(args)), 1, marks, read)
        if not answers:
            return None
        result: list[Term | None] = list(args)
        for index, value in zip(read, answers[0], strict=True):
            result[index] = value
        return result

    def call_once(self, pred: int, arity: int, inputs: Sequence[tuple[int, Term]],
                  number: int, keep: int) -> tuple[int, int]:
        """One call of a deterministic ``pred`` (the rule interpreter's, once per cycle):
        the integer output ``number`` and output ``keep`` recorded (the handle of a
        ``PL_record``, which the caller owns: a :class:`Record` frees it). As
        :meth:`solve`, with nothing else converted. A predicate with only its two outputs
        (a plan, see rules.pl's define_plan/3) called outside any other query takes
        its arguments from term references made once: five C calls in all (with the
        record's erasure later, six a cycle; eight before plans were predicates)."""
        if get_ident() != self._thread:
            self._attach_thread()
        if self.pending_seed is not None:
            self.give_seed()
        self.guarded += 1
        try:
            fid = PL_open_foreign_frame()
            outer_since = self._enter()
            try:
                if inputs or self.depth > 1 or self._outputs_thread != self._thread:
                    base = PL_new_term_refs(arity)
                    for index, value in inputs:
                        self._put_term(base + index, value, {})
                else:  # (bound inside the frame: discarding it unbinds them)
                    base = self._outputs
                if PL_call_predicate(None, Q_PASS, pred, base):
                    if not PL_get_int64(base + number, INT_REF):
                        raise KBError("internal: the interpreter's outcome is not a number")
                    return INT_BUF.value, PL_record(base + keep)
                exception = PL_exception(0)
                if not exception:
                    raise KBError("internal: the interpreter failed")
                record = PL_record(exception)
                PL_clear_exception()
                raise self._error_from(record)
            finally:
                self._leave(outer_since)
                PL_discard_foreign_frame(fid)
                self._release()
        finally:
            self.guarded -= 1
            self._stop_if_asked()

    def solve(self, pred: int, arity: int, inputs: Sequence[tuple[int, Term | None]],
              limit: int | None, marks: bool = False,
              outputs: Sequence[int] | None = None, keep: int | None = None) -> list[list[Term]]:
        """All (or the first ``limit``) solutions of ``pred`` called with the given
        ``(argument index, value)`` inputs; each solution lists the values of the
        ``outputs`` arguments (default: all); output ``keep`` is not converted but kept as a
        :class:`Record`. ``marks``: see :meth:`_get_term`."""
        if get_ident() != self._thread:
            self._attach_thread()
        if self.pending_seed is not None and pred not in self._seedless:
            self.give_seed()
        if outputs is None:
            outputs = range(arity)
        self.guarded += 1
        try:
            return self._solve(pred, arity, inputs, limit, marks, outputs, keep)
        finally:
            self.guarded -= 1
            self._stop_if_asked()

    def _solve(self, pred: int, arity: int, inputs: Sequence[tuple[int, Term | None]],
               limit: int | None, marks: bool, outputs: Sequence[int],
               keep: int | None) -> list[list[Term]]:
        """:meth:`solve`'s query, within its guard (see :attr:`guarded`)."""
        fid = PL_open_foreign_frame()
        try:
            base = PL_new_term_refs(arity) if arity else PL_new_term_ref()
            shared: dict[str, int] = {}
            try:
                for index, value in inputs:
                    if value is not None:
                        self._put_term(base + index, value, shared)
            except UnicodeEncodeError as error:
                raise KBError(f"text Prolog cannot hold: {error.object!r}") from None
            qid = PL_open_query(None, Q_CATCH, pred, base)
            answers: list[list[Term]] = []
            record = None
            outer_since = self._enter()
            try:
                get = self._get_term
                while limit is None or len(answers) < limit:
                    if not PL_next_solution(qid):
                        exception = PL_exception(qid)
                        if exception:
                            record = PL_record(exception)
                        break
                    seen: dict[str, Var] = {}
                    if keep is None:
                        answers.append([get(base + i, seen, marks) for i in outputs])
                    else:
                        answers.append([Record(self, PL_record(base + i)) if i == keep
                                        else get(base + i, seen, marks) for i in outputs])
            except (RecursionError, ctypes.ArgumentError) as error:
                if not _too_deep(error):
                    raise
                raise KBError("an answer is a cyclic or too deeply nested term") from None
            finally:
                PL_cut_query(qid)
                self._leave(outer_since)
            if record is not None:
                raise self._error_from(record)
            return answers
        finally:
            PL_discard_foreign_frame(fid)
            self._release()

    # ------------------------------------------------------------------ the random seed

    def seed_random(self, seed: int) -> None:
        """Seeds Prolog's random generator (random/1, random_member/2, ...) for repeatable
        runs: at once for what Prolog runs next, but given to SWI-Prolog only before a call
        that may run agent code -- seeding costs 2.8 million instructions (GMP), 29% of
        launching an agent, and launching N agents seeds N times, each seed replacing the
        last one before anything draws."""
        self.pending_seed = int(seed)

    def give_seed(self) -> None:
        """Gives SWI-Prolog the seed :meth:`seed_random` holds, if any."""
        seed, self.pending_seed = self.pending_seed, None
        if seed is not None:
            self.call("set_random", Struct("seed", (seed,)), module="system")

    def runs_no_agent_code(self, name: str, arity: int, module: str = "ga_kb") -> None:
        """Notes that ``module:name/arity`` runs no agent code: calling it leaves a seed
        pending (see :meth:`seed_random`)."""
        self._seedless.add(self.predicate(name, arity, module))

    # ------------------------------------------------------------------ releases

    def _release(self) -> None:
        """Unregisters the call's transient atoms and erases the records Python dropped."""
        while self._transient_atoms:
            PL_unregister_atom(self._transient_atoms.pop())
        while self._dead_records:
            PL_erase(self._dead_records.pop())

    # ------------------------------------------------------------------ internals

    def _attach_thread(self) -> None:
        """Gives the calling thread a Prolog engine (pyswip is not thread-safe: one at a time)."""
        if PL_thread_self() == -1 and PL_thread_attach_engine(None) < 0:
            raise KBError("cannot attach a Prolog engine to this thread")
        self._thread = get_ident()

    def _error_from(self, record: int) -> BaseException:
        """The exception to raise for a recorded Prolog exception: the Python exception a
        foreign predicate raised (see :func:`define_foreign`), or a PrologRuntimeError."""
        error = self._runtime_error(record)
        if error.term == "$aborted":
            return self._aborted()
        if error.term == _PYTHON_ERROR and self._python_errors:
            python_error = self._python_errors[-1]
            self._python_errors.clear()
            return python_error
        return error

    def _recorded(self, record: int) -> Term:
        """The Python value of a recorded term (the record stays)."""
        if get_ident() != self._thread:
            self._attach_thread()
        self.guarded += 1
        try:
            fid = PL_open_foreign_frame()
            try:
                t = PL_new_term_ref()
                PL_recorded(record, t)
                return self._get_term(t, {}, False)
            finally:
                PL_discard_foreign_frame(fid)
        finally:
            self.guarded -= 1
            self._stop_if_asked()

    def _runtime_error(self, record: int) -> PrologRuntimeError:
        """Turns a recorded exception term into a PrologRuntimeError (SWI's message text)."""
        fid = PL_open_foreign_frame()
        try:
            t = PL_new_term_ref()
            PL_recorded(record, t)
            PL_erase(record)
            term = self._get_term(t, {}, False)
            pred = self.predicate("error_message", 2, "ga_kb")
            base = PL_new_term_refs(2)
            PL_put_term(base, t)
            qid = PL_open_query(None, Q_CATCH, pred, base)
            try:
                ok = PL_next_solution(qid)
                message = text_of(base + 1, TEXT_FLAGS) if ok else format_term(term)
            finally:
                PL_cut_query(qid)
            return PrologRuntimeError(message, term)
        finally:
            PL_discard_foreign_frame(fid)


_TOO_DEEP_FOR_PYTHON = "cannot pass a cyclic term, or one nested over ~1,000 levels, to Python"


def _too_deep(error: BaseException) -> bool:
    """Python's recursion limit met converting a term (in Python, or in a ctypes call)."""
    return isinstance(error, RecursionError) or (
        isinstance(error, ctypes.ArgumentError) and "RecursionError" in str(error))


def define_foreign(engine: PrologCalls, module: str, name: str,
                   respond: Callable[[Term], Term | None], *, stretch: bool = True) -> None:
    """Defines ``module:name(+Request, -Reply)``: Prolog's call converts Request to a Python
    term, calls ``respond`` and unifies Reply with its answer (None: leaves Reply unbound).
    A Python exception in ``respond`` leaves Prolog as the exception ``'$ga_python'`` and is
    raised again where Python called Prolog (:meth:`PrologCalls.solve`). A call ends the running
    stretch (goalagent.kb.watchdog) unless ``stretch`` is False (a quick look that must not)."""

    def foreign(request: int, reply: int) -> int:
        if stretch:
            engine.stretch_since = None  # in Python now: not the watchdog's to time
        try:
            if not PL_is_acyclic(request):  # a cyclic list would be read for ever
                raise KBError(_TOO_DEEP_FOR_PYTHON)
            answer = respond(engine._get_term(request, {}, False))
            if answer is None:
                return 1
            t = PL_new_term_ref()
            engine._put_term(t, answer, {})
            return 1 if PL_unify(reply, t) else 0
        except BaseException as error:  # noqa: BLE001 - carried out of Prolog, re-raised
            t = PL_new_term_ref()
            if isinstance(error, PrologRuntimeError) and error.term == _INFERENCES_SPENT:
                # A nested query (a module call) used up the enclosing query's inference
                # limit: it is that query's limit, met where it called Python.
                PL_put_atom(t, engine._atom_handle(_INFERENCES_SPENT))
                return PL_raise_exception(t)
            engine._python_errors.append(KBError(_TOO_DEEP_FOR_PYTHON) if _too_deep(error)
                                         else error)
            PL_put_atom(t, engine._atom_handle(_PYTHON_ERROR))
            return PL_raise_exception(t)
        finally:
            if stretch:  # back to Prolog: a new stretch
                engine.stretch += 1
                engine.stretch_since = monotonic()

    callback = _FOREIGN_2(foreign)
    engine._foreign.append(callback)
    if not PL_register_foreign_in_module(module.encode(), name.encode(), 2,
                                         ctypes.cast(callback, c_void_p), 0):
        raise KBError(f"cannot define the foreign predicate {module}:{name}/2")
