"""Which SWI-Prolog goalagent runs on, and the one line a user gets when it cannot.

goalagent loads SWI-Prolog's shared library (``libswipl``) through pyswip; it is not a Python
package, so ``pip install goalagent`` cannot bring it. When it is missing, cannot be found or
is older than 9, the ``goalagent`` command prints :func:`install_line` (how to install it on
Debian/Ubuntu, macOS and conda) and exits with code 2; the Python API raises
:class:`SWIPrologMissing` with the same message. Standard library only: the command's
launcher imports it before anything that starts Prolog.
"""

from __future__ import annotations

OLDEST = (9, 0, 0)
"""The oldest SWI-Prolog goalagent supports (it is built and tested on 9.0.4)."""

_HOW = ("Debian/Ubuntu: sudo apt-get install swi-prolog-nox; macOS: brew install swi-prolog; "
        "conda: conda install -c conda-forge swi-prolog; then make sure `swipl` is on PATH "
        "(or set LIBSWIPL_PATH and SWI_HOME_DIR)")


class SWIPrologMissing(ImportError):
    """SWI-Prolog 9 could not be loaded (not installed, not found, or too old); the message
    is one line saying how to install it."""


def version_text(number: int) -> str:
    """``90004`` (SWI's ``PL_QUERY_VERSION``: major * 10000 + minor * 100 + patch) as
    ``9.0.4``."""
    return f"{number // 10000}.{number // 100 % 100}.{number % 100}"


def too_old(number: int) -> bool:
    """Whether the SWI-Prolog of version ``number`` (as ``PL_QUERY_VERSION`` gives it) is
    older than goalagent supports."""
    major, minor, patch = OLDEST
    return number < major * 10000 + minor * 100 + patch


def install_line(found: str) -> str:
    """The message for a user whose SWI-Prolog is unusable; ``found`` says what was found
    (``none (libswipl could not be loaded: ...)``, ``8.4.2``)."""
    oldest = ".".join(str(part) for part in OLDEST[:2])
    return f"goalagent needs SWI-Prolog {oldest} or newer, found {found}. Install it: {_HOW}"
