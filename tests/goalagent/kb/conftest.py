"""Fixtures of the mental-state tests: a blocks-world state with one goal, and an empty one;
each closed after its test."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from goalagent.kb import MentalState

from .states import BLOCKS_KNOWLEDGE, text


@pytest.fixture
def blocks() -> Iterator[MentalState]:
    """c on a, a and b on the table; the goal tower a-b-c (one goal of three facts)."""
    state = MentalState(
        "blocks",
        knowledge=BLOCKS_KNOWLEDGE,
        beliefs=[text("on(a, table)"), text("on(b, table)"), text("on(c, a)")],
    )
    assert state.adopt("on(a, b), on(b, c), on(c, table)")
    yield state
    state.close()


@pytest.fixture
def empty() -> Iterator[MentalState]:
    state = MentalState("empty")
    yield state
    state.close()
