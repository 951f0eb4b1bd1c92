"""``goalagent objects list | show NAME | forget NAME``: the known-object database (chapter 5).

The database is what ``learn(..., transfer)`` learned about each can (its parts'
descriptors, ``above`` relations, part models ĝ/ĥ and the functional pair) and what later cans
transfer from. The commands read it (or remove one object) at ``--db`` (default: the garbage
environment's default ``objects`` path). Everything printed is plain text: no Rich markup is
read from names that come from files, and their control characters (ANSI escapes) are shown
escaped (``goalagent.console.printable``, which ``LastingConsole`` applies to every string).
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.table import Table

from goalagent.console import LastingConsole, err_console, printable, user_error
from robot.paths import default_objects_path

DB_OPTION = Annotated[Path | None, typer.Option(
    "--db", help="The known-object database (default: the garbage environment's).")]
out_console = LastingConsole(highlight=False, soft_wrap=True, emoji=False)


def _open(db: Path | None):  # -> KnownObjectDatabase
    """The database at ``db`` (default path if None), or a user error naming the problem."""
    from behaviours.learners.known_objects import DatabaseError, KnownObjectDatabase

    path = db or default_objects_path()
    if db is not None and not path.exists():
        raise user_error(f"no known-object database at {path}")
    try:
        return KnownObjectDatabase(path)
    except DatabaseError as err:
        raise user_error(str(err)) from None


def list_objects(db: DB_OPTION = None) -> None:
    """List the known objects: parts, the functional pair, actions it took, its source."""
    database = _open(db)
    table = Table("object", "parts", "opens by", "N", "source", "can file")
    for known in database:
        opens = "-" if known.functional is None else (
            f"{known.functional.action}({known.functional.part}, {known.functional.theta:.3f})")
        table.add_row(*(printable(cell) for cell in (
            known.name, ", ".join(known.parts), opens, str(known.n_actions), known.source or "-",
            str(known.extra.get("can_file", "-")))))
    if not len(database):
        err_console.print(f"no known objects in {database.path}", markup=False)
        return
    out_console.print(table, markup=False)


def show_object(name: Annotated[str, typer.Argument(help="The object's name.")],
                db: DB_OPTION = None) -> None:
    """Show one known object: descriptors, relations, every pair model, the functional pair."""
    from behaviours.learners.known_objects import DatabaseError

    database = _open(db)
    try:
        known = database.get(name)
    except DatabaseError as err:
        raise user_error(str(err)) from None
    lines = [f"object {known.name} (learned with {known.n_actions} actions"
             + (f", transferred from {known.source})" if known.source else ", from scratch)")]
    for part, descriptor in known.parts.items():
        area, rect, square = (float(x) for x in descriptor)
        lines.append(f"  part {part}: area {area:.5f}, rectangleness {rect:.3f}, "
                     f"squareness {square:.3f}")
    lines += [f"  above({a}, {b})" for a, b in sorted(known.above)]
    if known.functional is not None:
        f = known.functional
        lines.append(f"  functional: {f.action} on {f.part} with theta {f.theta:.4f}")
    out_console.print("\n".join(lines), markup=False)
    table = Table("part", "action", "n", "g(theta) = b + c theta", "h(e) = d + e e_psi")
    for (part, action), model in known.models.items():
        table.add_row(printable(part), printable(action), str(model.n_samples_),
                      f"{model.g_intercept_:+.4f} {model.g_slope_:+.3f} theta",
                      f"{model.h_intercept_:+.4f} {model.h_slope_:+.3f} e")
    out_console.print(table, markup=False)


def forget_object(name: Annotated[str, typer.Argument(help="The object's name.")],
                  db: DB_OPTION = None) -> None:
    """Remove one known object (the file is rewritten atomically)."""
    from behaviours.learners.known_objects import DatabaseError

    database = _open(db)
    try:
        database.forget(name)
    except DatabaseError as err:
        raise user_error(str(err)) from None
    except OSError as err:  # the file cannot be replaced: it stays as it was
        raise user_error(f"cannot rewrite {database.path}: {err.strerror or err}") from None
    err_console.print(f"forgot {name}; {len(database)} known objects left in {database.path}",
                      markup=False)


def objects_app() -> typer.Typer:
    """The ``objects`` command group."""
    app = typer.Typer(name="objects", no_args_is_help=True,
                      help="The known objects that transfer learning (chapter 5) draws on.")
    app.command("list")(list_objects)
    app.command("show")(show_object)
    app.command("forget")(forget_object)
    return app
