"""goalagent: GOAL agents on SWI-Prolog, with environments reached through EIS."""
