"""docs/confinement-review.md, the review of the confinement against every predicate
SWI-Prolog's manual documents (issue 24), still says what confine.pl does: each row's
verdicts, without and with the sandbox, are computed again and compared."""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "scripts"))

import confinement_review as review  # noqa: E402


def test_every_row_of_the_review_holds():
    rows = review.read_doc()
    assert len(rows) > 700 and len({row.section for row in rows}) > 80
    judged = review.judge(rows)
    changed = [f"{row.section}: {row.indicator}: table {row.exists}, {row.plain}, "
               f"{row.sandbox}; now {now.exists}, {now.plain}, {now.sandbox}"
               for row, now in zip(rows, judged, strict=True)
               if (row.exists, row.plain, row.sandbox) != (now.exists, now.plain, now.sandbox)]
    assert not changed, ("the confinement changed: write docs/confinement-review.md again "
                         "(scripts/confinement_review.py) and check the rows:\n"
                         + "\n".join(changed))


def test_the_review_names_what_issue_24_closed():
    rows = {row.indicator: row for row in review.read_doc()}
    for indicator in ("working_directory/2", "unload_file/1", "prolog_alert_signal/2",
                      "sig_atomic/1", "set_output/1", "setenv/2", "engine_create/3"):
        assert rows[indicator].plain == "refused: process-wide", indicator
        assert rows[indicator].issue24 == "closed", indicator
    for indicator in ("nb_setval/2", "nb_getval/2", "flag/3", "recorded/3"):
        assert rows[indicator].plain == "agent" and rows[indicator].issue24 == "per agent"
    assert rows["phrase/2"].issue24 == "checked"
