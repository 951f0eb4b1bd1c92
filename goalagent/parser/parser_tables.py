"""The parser's tables, kept between processes: building the LALR parser from grammar.lark
costs about 0.3 s of CPU, loading the saved one about 0.03 s, and every ``goalagent`` command
parses something.

Written around lark's own ``Lark.save``/``Lark.load`` rather than lark's ``cache=`` option:
``cache=True`` keeps a pickle under a predictable name in the shared temporary folder, where
another account could plant one, and ``cache=PATH`` writes in place, so a process starting
beside one that writes may read half a file. Here the tables live in the user's cache folder
(``$XDG_CACHE_HOME/goalagent``), are written atomically and for the user alone, and are loaded
only when they are the user's own (:func:`ondisk.cache.read_own`) and were saved for this very
grammar, these options, this lark and this Python. Anything else -- no file, a stale or corrupt
one, a read-only home -- means the parser is built as before, and saved when the folder can be
written.
"""

from __future__ import annotations

import hashlib
import io
import sys
from typing import Any

import lark
from lark import Lark

from ondisk import write_atomically
from ondisk.cache import cache_folder, make_cache_folder, read_own

TABLES_FILE = "parser-tables.pickle"
MAX_TABLES_BYTES = 8 << 20
"""Larger than any saved parser of grammar.lark (about 0.2 MB): anything bigger is not ours."""


def tables_key(grammar: str, options: dict[str, Any]) -> bytes:
    """What the saved tables must have been made from: the grammar, the options, lark's and
    Python's versions (the first line of the file)."""
    made_from = repr((grammar, sorted(options.items()), lark.__version__,
                      sys.version_info[:2]))
    return b"goalagent parser tables " + hashlib.sha256(made_from.encode()).hexdigest().encode()


def parser(grammar: str, **options: Any) -> Lark:
    """``Lark(grammar, **options)``, from the saved tables when they match (see the module's
    docstring)."""
    key = tables_key(grammar, options)
    path = cache_folder() / TABLES_FILE
    saved = read_own(path, MAX_TABLES_BYTES)
    if saved is not None:
        first_line, _, tables = saved.partition(b"\n")
        if first_line == key:
            try:
                return Lark.load(io.BytesIO(tables))
            except Exception:  # noqa: BLE001 -- a corrupt cache is rebuilt, whatever it raises
                pass
    built = Lark(grammar, **options)
    content = io.BytesIO()
    content.write(key + b"\n")
    built.save(content)
    try:
        make_cache_folder(path.parent)
        write_atomically(path, content.getvalue())
        path.chmod(0o600)  # (a replaced file keeps its mode: one others could write is useless)
    except OSError:
        pass  # a cache that cannot be written is only slower
    return built
