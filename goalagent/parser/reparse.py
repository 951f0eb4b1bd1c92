"""Programs parsed once per process: parsing the same text of the same file again (each seed
of a reproduction, each agent a test makes from one file) gives a fresh copy of the first
parse instead of running lark and SWI-Prolog's reader over it again (60 ms for the garbage
agent, 0.5 ms to copy).

A parse also depends on what its ``#import``s found on disk: whether a file was next to the
program, which library an extension brought, what a file held. Those are ``observe``d while
the first parse runs, and looked at again before a copy is handed out; when any differs the
text is parsed anew. A parse that fails is not kept (the error is raised again by parsing).
The copy is unpickled from the kept bytes, so no caller shares an object with another.

Hand-written rather than ``functools.lru_cache``: the cache must check the observations
before a hit and hand out copies, neither of which lru_cache does.
"""

from __future__ import annotations

import hashlib
import pickle
import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable, Sequence
from contextvars import ContextVar
from typing import Any, TypeVar

T = TypeVar("T")

KEPT_BYTES = 32 * 2**20
"""The kept parses' pickles take at most this (the least recently used go first)."""

Observation = tuple[Callable[[], Any], Any]

_observations: ContextVar[list[Observation] | None] = ContextVar("observations", default=None)
_kept: OrderedDict[Hashable, tuple[bytes, tuple[Observation, ...]]] = OrderedDict()
_kept_bytes = 0
_lock = threading.Lock()


def observe(look: Callable[[], T]) -> T:
    """``look()``, noted (with what it gave) for the parse running now, if one is kept."""
    seen = look()
    observations = _observations.get()
    if observations is not None:
        observations.append((look, _fingerprint(seen)))
    return seen


def parsed_once(text: str, key: Hashable, parse: Callable[[], T]) -> T:
    """What ``parse()`` gives for ``text`` read as ``key`` says (its file, its start rule,
    options: all it depends on but the text and the observations): a copy of the kept result
    when every observation still holds. The text is kept as its digest."""
    key = (key, _fingerprint(text))
    with _lock:
        kept = _kept.get(key)
        if kept is not None:
            _kept.move_to_end(key)
    if kept is not None and all(_still(look, seen) for look, seen in kept[1]):
        _pass_on(kept[1])
        return pickle.loads(kept[0])
    observations: list[Observation] = []
    token = _observations.set(observations)
    try:
        result = parse()
    finally:
        _observations.reset(token)
    _pass_on(observations)
    _keep(key, pickle.dumps(result, protocol=pickle.HIGHEST_PROTOCOL), tuple(observations))
    return result


def _keep(key: Hashable, data: bytes, observations: tuple[Observation, ...]) -> None:
    """Keep a parse, dropping the least recently used ones beyond KEPT_BYTES."""
    global _kept_bytes
    with _lock:
        if key in _kept:
            _kept_bytes -= len(_kept.pop(key)[0])
        _kept[key] = (data, observations)
        _kept_bytes += len(data)
        while _kept_bytes > KEPT_BYTES:
            _kept_bytes -= len(_kept.popitem(last=False)[1][0])


def _pass_on(observations: Sequence[Observation]) -> None:
    """A parse inside another kept one: what it depends on, the outer one does too."""
    outer = _observations.get()
    if outer is not None:
        outer.extend(observations)


def _still(look: Callable[[], Any], seen: Any) -> bool:
    """Whether ``look()`` gives what it gave before (a look that now fails does not)."""
    try:
        return _fingerprint(look()) == seen
    except Exception:  # noqa: BLE001 - e.g. an imported file gone: parse again, which says so
        return False


def _fingerprint(seen: Any) -> Any:
    """What is kept of an observed value: a text (an imported file's) as its digest."""
    if isinstance(seen, str):
        return hashlib.blake2b(seen.encode("utf-8", "surrogatepass")).digest()
    return seen
