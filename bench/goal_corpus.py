"""How much of a corpus of public GOAL programs ``goalagent check`` accepts (issue 26).

    python bench/goal_corpus.py CORPUS [--refusals FILE]

CORPUS holds one folder per repository (``owner+name``), under it the files of one commit
per folder; ``CORPUS/manifest.tsv`` (repository, commit folder, path, blob; one line per
unique file version) names the files to check, each in the commit folder that first holds
it, so the files it uses are beside it. Without a manifest every .goal, .mas2g, .mod2g,
.test2g and .act2g file under CORPUS is checked. Nothing is fetched: the corpus is made
beforehand (the numbers in bench/README.md name how).

Prints the files and repositories checked, how many ``check`` accepts, and the refusals
grouped by their message (quoted names, numbers and paths blanked), largest group first;
``--refusals FILE`` writes every refusal, one ``path<TAB>first error`` line each, for
judging which of them are valid GOAL. ``--judged FILE`` (bench/goal_corpus_judged.tsv)
lists refusals judged, by reading the files, not to be valid GOAL: the share of valid files
that check is then printed, with the refusals left by cause, and the verdict GOAL's own
validator test resources (``analyzer/`` folders) get compared with GOAL's.
"""

from __future__ import annotations

import argparse
import re
import sys
from collections import Counter
from pathlib import Path

# Run as a script, this file's folder comes first on sys.path, where bench/sim.py would hide
# the sim package the robot extension needs: put the repository root there.
sys.path[0] = str(Path(__file__).resolve().parents[1])

from goalagent.checking import check_file  # noqa: E402

SUFFIXES = (".goal", ".mas2g", ".mod2g", ".test2g", ".act2g")


def corpus_files(root: Path) -> list[tuple[str, Path]]:
    """(repository, file) of every file to check."""
    manifest = root / "manifest.tsv"
    if manifest.is_file():
        rows = [line.rstrip("\n").split("\t") for line in manifest.open(encoding="utf-8")]
        return [(repo, root / repo / commit / path) for repo, commit, path, _ in rows]
    return [(path.relative_to(root).parts[0], path) for path in sorted(root.rglob("*"))
            if path.suffix in SUFFIXES and path.is_file()]


def first_error(lines: list[str]) -> str:
    """The first line of a refusal that is not a warning."""
    return next((line for line in lines if ": warning: " not in line
                 and "checked as part of" not in line), "")


def cause(error: str) -> str:
    """An error's message with its place, quoted texts, numbers and names blanked, so that
    refusals of one kind group together."""
    message = re.sub(r"^.*?:\d+:\d+: ", "", error)
    message = re.sub(r"'[^']*'|\"[^\"]*\"|`[^`]*`", "Q", message)
    message = re.sub(r"\b\w+/\d+\b", "N/A", message)
    message = re.sub(r"\(known: .*\)$|; its parameters: .*$", "", message)
    return message[:100]


def read_judged(path: Path) -> list[tuple[re.Pattern[str], re.Pattern[str], str]]:
    """The judgments: (path regex, error regex, reason) per line, comments skipped."""
    judged = []
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.startswith("#"):
            where, error, reason = line.split("\t")
            judged.append((re.compile(where), re.compile(error), reason))
    return judged


def invalid_reason(judged, repo: str, path: Path, error: str) -> str | None:
    """Why a refused file is not valid GOAL, if judged so."""
    inside = f"{repo}/{'/'.join(path.parts[path.parts.index(repo) + 2:])}"
    return next((reason for where, wrong, reason in judged  # the file, or the one it uses
                 if (where.search(inside) or where.search(error)) and wrong.search(error)),
                None)


def report_judged(judged, files, refused: dict[Path, str]) -> None:
    """The valid share, the refusals left by cause, and GOAL's own verdicts matched."""
    invalid: dict[Path, str] = {}
    for repo, path in files:
        if path in refused:
            reason = invalid_reason(judged, repo, path, refused[path])
            if reason is not None:
                invalid[path] = reason
    valid = len(files) - len(invalid)
    left = {path: error for path, error in refused.items() if path not in invalid}
    print(f"{len(invalid)} refused files judged not valid GOAL; of the {valid} valid files "
          f"{valid - len(left)} check ({(valid - len(left)) / max(valid, 1):.1%})")
    for reason, count in Counter(invalid.values()).most_common():
        print(f"  invalid {count:4d}  {reason}")
    for message, count in Counter(cause(error) for error in left.values()).most_common():
        print(f"  refused {count:4d}  {message}")
    for error in sorted(left.values()):
        print(f"    {error}")
    own = [(repo, path) for repo, path in files if "/analyzer/" in str(path)
           and re.fullmatch(r"test(_[A-Z0-9_]+)?\.goal|test_[A-Z0-9_]+\.mas2g|template\.mas2g",
                            path.name)]  # the files GOAL's validator tests give verdicts on
    if own:  # GOAL's verdict: an error when a judgment names the file whatever its error
        matched = sum(1 for repo, path in own
                      if (invalid_reason(judged, repo, path, "any error") is not None)
                      == (path in refused))
        print(f"GOAL's validator resources: {matched} of {len(own)} verdicts as GOAL's "
              f"({matched / len(own):.1%})")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("corpus", type=Path)
    parser.add_argument("--refusals", type=Path)
    parser.add_argument("--judged", type=Path)
    args = parser.parse_args(argv)
    files = corpus_files(args.corpus)
    refused: list[tuple[str, str]] = []
    for _, path in files:
        lines: list[str] = []
        if not check_file(path, False, lines.append):
            refused.append((str(path), first_error(lines)))
    repos = {repo for repo, _ in files}
    accepted = len(files) - len(refused)
    print(f"{len(files)} files from {len(repos)} repositories: {accepted} accepted "
          f"({accepted / max(len(files), 1):.1%}), {len(refused)} refused")
    for message, count in Counter(cause(error) for _, error in refused).most_common():
        print(f"{count:5d}  {message}")
    if args.judged is not None:
        report_judged(read_judged(args.judged), files, {Path(p): e for p, e in refused})
    if args.refusals is not None:
        args.refusals.write_text("".join(f"{path}\t{error}\n" for path, error in refused),
                                 encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
