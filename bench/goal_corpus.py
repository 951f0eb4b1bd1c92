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
judging which of them are valid GOAL.
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


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("corpus", type=Path)
    parser.add_argument("--refusals", type=Path)
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
    if args.refusals is not None:
        args.refusals.write_text("".join(f"{path}\t{error}\n" for path, error in refused),
                                 encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
