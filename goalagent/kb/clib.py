"""libswipl's C foreign interface as goalagent uses it: typed ctypes handles on its
functions, its type and flag constants, and the output buffers of the getters; and how SWI
is started.

pyswip loads ``libswipl``; we declare our own handles (pyswip's keep their own argument
types) because the raw interface is an order of magnitude faster than the string API. Only
goalagent.kb (engine.py, conversion.py, watchdog.py) uses this module.

SWI is started here, before pyswip would start it with ``--nosignals``: that flag also
turns off SWI's C-stack guard, so writing or reading a term nested ~100,000 deep (an
agent's ``term_to_atom/2``, ``format/2``, ``print``) was a segmentation fault of the whole
process. With SWI's signal handling on, its writer and reader meet the C-stack limit as a
``resource_error(c_stack)`` in the query, which the rule's condition catches like any other
error. SWI then also takes over other signals (SIGTERM, SIGHUP, SIGALRM, SIGPIPE, SIGILL,
SIGBUS, ...); those are given back exactly as they were before SWI started, so Python's
Ctrl-C/SIGTERM handling (goalagent/runner.py, watchdog.py) and subprocesses see what
they did with ``--nosignals``. SWI keeps only SIGSEGV (the guard: a C-stack overflow in a
guarded built-in longjmps back with the error, any other segmentation fault still ends
the process after SWI's crash report) and SIGUSR2 (its thread alert, as with
``--nosignals``). Its background garbage-collection thread stays off, as with
``--nosignals``.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import importlib
import importlib.util
import signal
import sys
from ctypes import POINTER, byref, c_char_p, c_double, c_int, c_int64, c_size_t, c_uint, c_void_p
from types import ModuleType

from goalagent.kb.errors import KBError
from goalagent.swi import SWIPrologMissing, install_line, too_old, version_text

SWI_KEEPS = frozenset({signal.SIGSEGV, signal.SIGUSR2})
"""The signals whose handlers SWI installs and keeps (see the module docstring)."""
_SIGACTION_BYTES = 512  # more than any libc's struct sigaction (glibc x86-64: 152)
_HANDLER_BYTES = ctypes.sizeof(c_void_p)  # the handler is the struct's first member
_swi_argv: ctypes.Array | None = None  # SWI keeps pointers into its argv: kept alive here
PL_QUERY_VERSION = 10  # PL_query's question for the version (SWI-Prolog.h): 90004 for 9.0.4


def _dispositions(libc: ctypes.CDLL) -> dict[int, ctypes.Array]:
    """Each signal's current ``struct sigaction``, as opaque bytes."""
    saved = {}
    for signum in range(1, signal.NSIG):
        action = ctypes.create_string_buffer(_SIGACTION_BYTES)
        if libc.sigaction(signum, None, action) == 0:
            saved[signum] = action
    return saved


def _initialise_swi(core: ModuleType) -> None:
    """Starts SWI with its signal handling on (pyswip's own PL_initialise then does
    nothing), then gives back every signal handler it replaced but those of ``SWI_KEEPS``."""
    global _swi_argv
    libc = ctypes.CDLL(None, use_errno=True)
    before = _dispositions(libc)
    args = [b"./", b"-q"]  # pyswip's arguments without --nosignals
    if core.SWI_HOME_DIR:
        args.append(f"--home={core.SWI_HOME_DIR}".encode())
    _swi_argv = (c_char_p * (len(args) + 1))(*args, None)
    initialise = ctypes.CDLL(core._lib._name, mode=ctypes.RTLD_GLOBAL).PL_initialise
    initialise.argtypes = (c_int, POINTER(c_char_p))
    if not initialise(len(args), _swi_argv):
        raise ImportError("SWI-Prolog could not be initialised")
    for signum, action in _dispositions(libc).items():
        old = before.get(signum)
        if signum not in SWI_KEEPS and old is not None and \
                action.raw[:_HANDLER_BYTES] != old.raw[:_HANDLER_BYTES]:
            libc.sigaction(signum, old, None)


def _load_pyswip() -> ModuleType:
    """pyswip's ``core`` module, with SWI started by :func:`_initialise_swi` between
    loading ``libswipl`` (pyswip.core) and pyswip's own start (its package import). If
    pyswip was imported before goalagent, SWI already runs as pyswip started it."""
    if "pyswip" in sys.modules:
        return importlib.import_module("pyswip.core")
    spec = importlib.util.find_spec("pyswip")
    if spec is None or spec.loader is None:
        raise ImportError("pyswip is not installed")
    package = importlib.util.module_from_spec(spec)
    sys.modules["pyswip"] = package  # its __init__ not run yet: it would start SWI
    try:
        try:
            core = importlib.import_module("pyswip.core")  # finds and loads libswipl only
        except (ImportError, OSError) as error:  # none found, or one that does not load
            reason = " ".join(str(error).split())
            raise SWIPrologMissing(install_line(f"none ({reason})")) from None
        _check_version(core._lib._name)
        _initialise_swi(core)
        spec.loader.exec_module(package)
    except BaseException:
        for name in [name for name in sys.modules if name.partition(".")[0] == "pyswip"]:
            del sys.modules[name]
        raise
    return core


def _check_version(library: str) -> None:
    """Refuse a libswipl older than goalagent supports (``SWIPrologMissing``), before it
    is started."""
    query = ctypes.CDLL(library).PL_query
    query.restype = ctypes.c_int64
    query.argtypes = (c_int,)
    number = query(PL_QUERY_VERSION)
    if too_old(number):
        raise SWIPrologMissing(install_line(version_text(number)))


_pyswip_core = _load_pyswip()
LIB = ctypes.CDLL(_pyswip_core._lib._name, mode=ctypes.RTLD_GLOBAL)

term_t = c_size_t
atom_t = c_size_t


def _declare(name: str, restype: object, *argtypes: object) -> ctypes._CFuncPtr:
    """Our own typed handle on a libswipl function (pyswip's handles keep their own types)."""
    func = getattr(LIB, name)
    func.restype = restype
    func.argtypes = argtypes
    return func


PL_open_foreign_frame = _declare("PL_open_foreign_frame", c_size_t)
PL_discard_foreign_frame = _declare("PL_discard_foreign_frame", None, c_size_t)
PL_new_term_ref = _declare("PL_new_term_ref", term_t)
PL_new_term_refs = _declare("PL_new_term_refs", term_t, c_int)
PL_copy_term_ref = _declare("PL_copy_term_ref", term_t, term_t)
PL_predicate = _declare("PL_predicate", c_void_p, c_char_p, c_int, c_char_p)
PL_open_query = _declare("PL_open_query", c_void_p, c_void_p, c_int, c_void_p, term_t)
PL_next_solution = _declare("PL_next_solution", c_int, c_void_p)
PL_cut_query = _declare("PL_cut_query", c_int, c_void_p)
PL_call_predicate = _declare("PL_call_predicate", c_int, c_void_p, c_int, c_void_p, term_t)
PL_clear_exception = _declare("PL_clear_exception", None)
PL_exception = _declare("PL_exception", term_t, c_void_p)
PL_record = _declare("PL_record", c_void_p, term_t)
PL_recorded = _declare("PL_recorded", c_int, c_void_p, term_t)
PL_erase = _declare("PL_erase", None, c_void_p)
PL_term_type = _declare("PL_term_type", c_int, term_t)
PL_get_atom = _declare("PL_get_atom", c_int, term_t, POINTER(atom_t))
PL_get_int64 = _declare("PL_get_int64", c_int, term_t, POINTER(c_int64))
PL_get_float = _declare("PL_get_float", c_int, term_t, POINTER(c_double))
PL_get_nchars = _declare("PL_get_nchars", c_int, term_t, POINTER(c_size_t), POINTER(c_void_p),
                         c_uint)
PL_get_name_arity = _declare("PL_get_name_arity_sz", c_int, term_t, POINTER(atom_t),
                             POINTER(c_size_t))
PL_get_arg = _declare("_PL_get_arg_sz", c_int, c_size_t, term_t, term_t)
PL_get_list = _declare("PL_get_list", c_int, term_t, term_t, term_t)
PL_is_acyclic = _declare("PL_is_acyclic", c_int, term_t)
PL_put_variable = _declare("PL_put_variable", c_int, term_t)
PL_put_atom = _declare("PL_put_atom", c_int, term_t, atom_t)
PL_put_int64 = _declare("PL_put_int64", c_int, term_t, c_int64)
PL_put_float = _declare("PL_put_float", c_int, term_t, c_double)
PL_put_chars = _declare("PL_put_chars", c_int, term_t, c_int, c_size_t, c_char_p)
PL_put_nil = _declare("PL_put_nil", c_int, term_t)
PL_put_term = _declare("PL_put_term", c_int, term_t, term_t)
PL_put_term_from_chars = _declare("PL_put_term_from_chars", c_int, term_t, c_int, c_size_t,
                                  c_char_p)
PL_cons_list = _declare("PL_cons_list", c_int, term_t, term_t, term_t)
PL_cons_functor_v = _declare("PL_cons_functor_v", c_int, term_t, c_size_t, term_t)
PL_new_functor = _declare("PL_new_functor_sz", c_size_t, atom_t, c_size_t)
PL_new_atom = _declare("PL_new_atom_mbchars", atom_t, c_int, c_size_t, c_char_p)
PL_register_atom = _declare("PL_register_atom", None, atom_t)
PL_unregister_atom = _declare("PL_unregister_atom", None, atom_t)
PL_unify = _declare("PL_unify", c_int, term_t, term_t)
PL_raise_exception = _declare("PL_raise_exception", c_int, term_t)
PL_register_foreign_in_module = _declare("PL_register_foreign_in_module", c_int, c_char_p,
                                    c_char_p, c_int, c_void_p, c_int)
PL_thread_self = _declare("PL_thread_self", c_int)
PL_thread_attach_engine = _declare("PL_thread_attach_engine", c_int, c_void_p)
PL_thread_destroy_engine = _declare("PL_thread_destroy_engine", c_int)
PL_chars_to_term = _declare("PL_chars_to_term", c_int, c_char_p, term_t)
PL_call = _declare("PL_call", c_int, term_t, c_void_p)


class _Mpz(ctypes.Structure):
    """GMP's mpz_t, read for its size only."""

    _fields_ = [("alloc", c_int), ("size", c_int), ("limbs", c_void_p)]


PL_get_mpz = _declare("PL_get_mpz", c_int, term_t, POINTER(_Mpz))
_mpz_clear = ctypes.CDLL(ctypes.util.find_library("gmp") or "libgmp.so.10").__gmpz_clear
_mpz_clear.restype, _mpz_clear.argtypes = None, (POINTER(_Mpz),)


def integer_bits(t: int) -> int:
    """About how many bits the integer in term ref ``t`` has (its GMP limbs), without
    converting it: writing a huge one in decimal takes SWI-Prolog seconds, uninterruptibly."""
    mpz = _Mpz()
    if not PL_get_mpz(t, byref(mpz)):
        return 0
    try:
        return abs(mpz.size) * 64
    finally:
        _mpz_clear(byref(mpz))


def _call_text(goal: bytes) -> bool:
    """Runs a goal given as text, once (used while starting, before the engine exists)."""
    frame = PL_open_foreign_frame()
    try:
        term = PL_new_term_ref()
        return bool(PL_chars_to_term(goal, term) and PL_call(term, None))
    finally:
        PL_discard_foreign_frame(frame)


# With signal handling on SWI starts a thread for atom and clause garbage collection;
# --nosignals had none: collect in the thread that needs it, as before.
if not _call_text(b"set_prolog_gc_thread(false)"):
    raise ImportError("SWI-Prolog's garbage-collection thread could not be stopped")

PL_VARIABLE, PL_ATOM, PL_INTEGER, PL_RATIONAL, PL_FLOAT, PL_STRING = 1, 2, 3, 4, 5, 6
PL_TERM, PL_NIL, PL_LIST_PAIR = 7, 8, 10
Q_CATCH = 0x04 | 0x08  # PL_Q_NODEBUG | PL_Q_CATCH_EXCEPTION
Q_PASS = 0x04 | 0x10  # PL_Q_NODEBUG | PL_Q_PASS_EXCEPTION: PL_exception(0) has it
REP_UTF8 = 0x00100000
CVT_ATOM, CVT_STRING, CVT_INTEGER, CVT_VARIABLE, CVT_WRITEQ = 0x1, 0x2, 0x8, 0x40, 0x200
TEXT_FLAGS = CVT_ATOM | CVT_STRING | REP_UTF8
PUT_STRING = 6 | REP_UTF8  # PL_STRING type for PL_put_chars
INT64_MIN, INT64_MAX = -(2**63), 2**63 - 1




# Output buffers for the getters: Prolog runs on one thread at a time and every value is
# read right after the call that fills it, so one set of buffers serves all calls.
ATOM_BUF, SIZE_BUF, INT_BUF, FLOAT_BUF = atom_t(), c_size_t(), c_int64(), c_double()
ATOM_REF, SIZE_REF = byref(ATOM_BUF), byref(SIZE_BUF)
INT_REF, FLOAT_REF = byref(INT_BUF), byref(FLOAT_BUF)


def text_of(t: int, flags: int) -> str:
    """The text of an atom/string/number term (UTF-8) or raises on failure."""
    length = c_size_t()
    ptr = c_void_p()
    if not PL_get_nchars(t, byref(length), byref(ptr), flags):
        raise KBError("cannot read the text of a Prolog term")
    return ctypes.string_at(ptr.value, length.value).decode("utf-8")
