"""libswipl's C foreign interface as goalagent uses it: typed ctypes handles on its
functions, its type and flag constants, and the output buffers of the getters.

pyswip loads and initialises ``libswipl``; we declare our own handles (pyswip's keep their
own argument types) because the raw interface is an order of magnitude faster than the
string API. Only goalagent.kb (engine.py, conversion.py) uses this module.
"""

from __future__ import annotations

import ctypes
from ctypes import POINTER, byref, c_char_p, c_double, c_int, c_int64, c_size_t, c_uint, c_void_p

from pyswip import core as _pyswip_core  # loads libswipl and runs PL_initialise once

from goalagent.kb.errors import KBError

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
PL_compare = _declare("PL_compare", c_int, term_t, term_t)
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

PL_VARIABLE, PL_ATOM, PL_INTEGER, PL_RATIONAL, PL_FLOAT, PL_STRING = 1, 2, 3, 4, 5, 6
PL_TERM, PL_NIL, PL_LIST_PAIR = 7, 8, 10
Q_CATCH = 0x04 | 0x08  # PL_Q_NODEBUG | PL_Q_CATCH_EXCEPTION
Q_PASS = 0x04 | 0x10  # PL_Q_NODEBUG | PL_Q_PASS_EXCEPTION: PL_exception(0) has it
REP_UTF8 = 0x00100000
CVT_ATOM, CVT_STRING, CVT_INTEGER, CVT_WRITEQ = 0x1, 0x2, 0x8, 0x200
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
