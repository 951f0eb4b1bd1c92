"""The blocks world of GOAL's classic example agents: blocks stacked on each other or the table.

Percepts (every cycle, the whole current state): ``block(X)`` for every block and ``on(X, Y)``
for every block, ``Y`` a block or ``table``. Action ``move(X, Y)`` puts block ``X`` on block
``Y`` or on ``table``; it is refused (world unchanged) unless ``X`` and ``Y`` are clear, differ,
and ``X`` is not already on ``Y``.

Init parameters: ``state = [on(a,b), on(b,table), ...]`` (every block placed exactly once, no
cycles); without it, ``blocks`` blocks (default 5) in random towers drawn with ``seed``
(default 0). ``robots`` (default 1) entities of type ``robot`` act on the same world: one is
called ``robot``, several ``robot1``, ``robot2``, ...
"""

from __future__ import annotations

import random
import string
from collections.abc import Iterable

from goalagent.eis.exceptions import ActionRefused, ManagementException
from goalagent.eis.pyenv import PerceptLike, PythonEnvironment, action
from goalagent.kb.terms import Struct, format_term

TABLE = "table"
MAX_BLOCKS = 10_000


def block_names(count: int) -> list[str]:
    """Names for ``count`` blocks: a, b, c, ... or b1, b2, ... beyond 26."""
    if count <= 26:
        return list(string.ascii_lowercase[:count])
    return [f"b{index}" for index in range(1, count + 1)]


def random_towers(blocks: list[str], rng: random.Random) -> dict[str, str]:
    """A random stacking of ``blocks``: each goes on the table or on top of an earlier tower."""
    order = list(blocks)
    rng.shuffle(order)
    on: dict[str, str] = {}
    tops: list[str] = []
    for block in order:
        if tops and rng.random() < 0.6:
            index = rng.randrange(len(tops))
            on[block] = tops[index]
            tops[index] = block
        else:
            on[block] = TABLE
            tops.append(block)
    return on


def parse_state(state: list[object]) -> dict[str, str]:
    """Block -> what it is on, from ``[on(a,b), on(b,table), ...]``; ManagementException if bad."""
    on: dict[str, str] = {}
    for item in state:
        if not (
            isinstance(item, Struct)
            and item.name == "on"
            and item.arity == 2
            and all(isinstance(arg, str) for arg in item.args)
        ):
            shown = format_term(item) if isinstance(item, (Struct, str, int, float, list)) else item
            raise ManagementException(
                "blocksworld: state entries must be on(Block, BlockOrTable) with names, "
                f"got {shown}"
            )
        block, below = str(item.args[0]), str(item.args[1])
        if block == TABLE:
            raise ManagementException("blocksworld: the table cannot be put on anything")
        if block in on:
            raise ManagementException(f"blocksworld: block {block} is placed twice in state")
        on[block] = below
    for block, below in on.items():
        if below != TABLE and below not in on:
            raise ManagementException(
                f"blocksworld: on({block},{below}) but {below} is not placed; add on({below}, ...)"
            )
    supported: dict[str, str] = {}
    for block, below in on.items():
        if below != TABLE:
            if below in supported:
                raise ManagementException(
                    f"blocksworld: both {supported[below]} and {block} are on {below}"
                )
            supported[below] = block
    for block in on:
        seen = {block}
        below = on[block]
        while below != TABLE:
            if below in seen:
                raise ManagementException(f"blocksworld: the state has a cycle through {block}")
            seen.add(below)
            below = on[below]
    return on


def initial_towers(env: str, params: dict[str, object]) -> dict[str, str]:
    """The towers given by init parameter ``state``, else ``blocks`` random ones from ``seed``
    (block -> what it is on); shared by the blocks and tower worlds."""
    if "state" in params:
        state = params["state"]
        assert isinstance(state, list)
        return parse_state(state)
    count = params.get("blocks", 5)
    if not isinstance(count, int) or not 0 <= count <= MAX_BLOCKS:
        raise ManagementException(f"{env}: blocks must be 0 to {MAX_BLOCKS}, got {count}")
    seed = params.get("seed", 0)
    assert isinstance(seed, int)
    return random_towers(block_names(count), random.Random(seed))


class BlocksWorld(PythonEnvironment):
    """Blocks on a table, moved one at a time with ``move(X, Y)``."""

    name = "blocksworld"
    default_entity_type = "robot"
    parameters = {"state": list, "blocks": int, "seed": int, "robots": int}

    def on_init(self, params: dict[str, object]) -> None:
        """Build the tower set from ``state`` or a seeded random one."""
        robots = params.get("robots", 1)
        if not isinstance(robots, int) or robots < 1:
            raise ManagementException(f"{self.name}: robots must be at least 1, got {robots}")
        self.robots = robots
        self.on = initial_towers(self.name, params)

    def initial_entities(self) -> dict[str, str]:
        """One ``robot``, or ``robot1`` ... ``robotN``."""
        if self.robots == 1:
            return {"robot": self.default_entity_type}
        names = [f"robot{index}" for index in range(1, self.robots + 1)]
        return {name: self.default_entity_type for name in names}

    def is_clear(self, block: str) -> bool:
        """True when nothing is on ``block`` (the table is always clear)."""
        return block == TABLE or block not in self.on.values()

    def percepts(self, entity: str) -> Iterable[PerceptLike]:
        """``block(X)`` and ``on(X, Y)`` for every block, sorted."""
        blocks = sorted(self.on)
        return [("block", block) for block in blocks] + [
            ("on", block, self.on[block]) for block in blocks
        ]

    def check_block(self, block: str, what: str) -> None:
        """Refuse when ``block`` is not a block of this world."""
        if block not in self.on:
            raise ActionRefused(f"{what}: {block} is not a block")

    @action("move")
    def move(self, entity: str, block: str, target: str) -> None:
        """Put ``block`` on ``target`` (a block or the table) when both are clear."""
        what = f"move({block},{target})"
        self.check_block(block, what)
        if target != TABLE:
            self.check_block(target, what)
        if block == target:
            raise ActionRefused(f"{what}: a block cannot be put on itself")
        if self.on[block] == target:
            raise ActionRefused(f"{what}: {block} is already on {target}")
        if not self.is_clear(block):
            raise ActionRefused(f"{what}: {block} is not clear")
        if not self.is_clear(target):
            raise ActionRefused(f"{what}: {target} is not clear")
        self.on[block] = target
