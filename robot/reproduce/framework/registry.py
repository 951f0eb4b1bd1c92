"""The studies by name: ``NAME`` is the module ``robot.reproduce.studies.<NAME with - as _>``
and its ``STUDY``. Helpers the studies share live in ``robot.reproduce.studies.common``."""

from __future__ import annotations

import difflib
import importlib
import pkgutil

from robot.reproduce.framework.study import NAME_PATTERN, Study

STUDIES = "robot.reproduce.studies"


class UnknownStudy(LookupError):
    """No study has that name (the message lists the close ones)."""


def module_name(name: str) -> str:
    """The module of study ``name``: ``xcs-mux`` -> ``robot.reproduce.studies.xcs_mux``."""
    return f"{STUDIES}.{name.replace('-', '_')}"


def find(name: str) -> Study:
    """The study called ``name``, or UnknownStudy naming the closest known ones."""
    if NAME_PATTERN.fullmatch(name):
        try:
            module = importlib.import_module(module_name(name))
        except ModuleNotFoundError as error:
            if error.name != module_name(name):
                raise
        else:
            study = getattr(module, "STUDY", None)
            if isinstance(study, Study) and study.name == name:
                return study
    raise UnknownStudy(_unknown(name))


def registered() -> list[Study]:
    """Every study, by name."""
    package = importlib.import_module(STUDIES)
    found = []
    for info in pkgutil.iter_modules(package.__path__):
        if info.ispkg:
            continue
        study = getattr(importlib.import_module(f"{STUDIES}.{info.name}"), "STUDY", None)
        if isinstance(study, Study):
            found.append(study)
    return sorted(found, key=lambda study: study.name)


def _unknown(name: str) -> str:
    names = [study.name for study in registered()]
    close = difflib.get_close_matches(name, names, n=3, cutoff=0.5)
    hint = f" (did you mean {' or '.join(repr(c) for c in close)}?)" if close else ""
    return (f"no study called {name!r}{hint}; known: {', '.join(names) or 'none'} "
            "(goalagent reproduce --list)")
