"""The blocks world of GOAL's classic example agents: blocks stacked on each other or the table.

GOAL's vocabulary (its blocksworld.jar): the entity is ``gripper`` (type ``gripper``); percepts
(every cycle, the whole current state) ``on(X, Y)`` for every block, ``Y`` a block or
``table`` -- and ``block(X)`` for every block, which GOAL's environment does not send; action
``move(X, Y)`` puts block ``X`` on block ``Y`` or on ``table``; it is refused (world unchanged)
unless ``X`` and ``Y`` are clear, differ, and ``X`` is not already on ``Y``.

Init parameters: GOAL's ``start = [2, 3, 0, 5, 0, 7, 0]`` (block ``bN`` sits on the block
numbered by the N-th number, 0 being the table) or ``start = "file.txt"`` (the same numbers in
a text file, looked for next to the system's .mas2g, then in the working directory), and
``gui`` (accepted and ignored: there is no display). goalagent's own, kept as aliases:
``state = [on(a,b), on(b,table), ...]`` (every block placed exactly once, no cycles);
without either, ``blocks`` blocks (default 5) in random towers drawn with ``seed`` (default
0). ``grippers`` (alias ``robots``, default 1) entities act on the same world: one is called
``gripper``, several ``gripper1``, ``gripper2``, ...
"""

from __future__ import annotations

import random
import string
from collections.abc import Iterable
from pathlib import Path

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


def parse_start(env: str, start: list[object] | str, home: Path | None) -> dict[str, str]:
    """Block -> what it is on, from GOAL's start numbers (a list, or a file of them):
    the N-th number says what block bN sits on, 0 the table."""
    if isinstance(start, str):
        start = _start_file(env, start, home)
    count = len(start)
    on: dict[str, str] = {}
    for index, below in enumerate(start, 1):
        if not isinstance(below, int) or isinstance(below, bool) or not 0 <= below <= count:
            raise ManagementException(f"{env}: start numbers must be 0 (the table) to "
                                      f"{count} (a block), got {below}")
        if below == index:
            raise ManagementException(f"{env}: start puts b{index} on itself")
        on[f"b{index}"] = TABLE if below == 0 else f"b{below}"
    check_towers(env, on)
    return on


def _start_file(env: str, name: str, home: Path | None) -> list[object]:
    """The numbers of a start file (next to the system's .mas2g, else the working one)."""
    candidates = [home / name] if home is not None else []
    candidates.append(Path(name))
    for path in candidates:
        if path.is_file():
            try:
                words = path.read_text(encoding="utf-8").split()
            except (OSError, UnicodeDecodeError) as error:
                raise ManagementException(f"{env}: cannot read start file {path}: {error}") \
                    from None
            if len(words) > MAX_BLOCKS or not all(word.isdigit() for word in words):
                raise ManagementException(f"{env}: start file {path} must hold at most "
                                          f"{MAX_BLOCKS} whole numbers")
            return [int(word) for word in words]
    raise ManagementException(f"{env}: no start file {name} "
                              f"({' or '.join(str(c) for c in candidates)})")


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
    check_towers("blocksworld", on)
    return on


def check_towers(env: str, on: dict[str, str]) -> None:
    """ManagementException unless every block carries at most one and no block is (via
    others) on itself."""
    supported: dict[str, str] = {}
    for block, below in on.items():
        if below != TABLE:
            if below in supported:
                raise ManagementException(
                    f"{env}: both {supported[below]} and {block} are on {below}"
                )
            supported[below] = block
    for block in on:
        seen = {block}
        below = on[block]
        while below != TABLE:
            if below in seen:
                raise ManagementException(f"{env}: the state has a cycle through {block}")
            seen.add(below)
            below = on[below]


def initial_towers(env: str, params: dict[str, object],
                   home: Path | None = None) -> dict[str, str]:
    """The towers given by init parameter ``start`` (GOAL's) or ``state``, else ``blocks``
    random ones from ``seed`` (block -> what it is on); shared by the blocks and tower
    worlds. ``home``: where a start file is looked for first."""
    if "start" in params:
        if "state" in params:
            raise ManagementException(f"{env}: give start or state, not both")
        start = params["start"]
        assert isinstance(start, (list, str))
        return parse_start(env, start, home)
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
    default_entity_type = "gripper"
    parameters = {"start": list | str, "gui": object, "state": list, "blocks": int,
                  "seed": int, "grippers": int, "robots": int}

    def on_init(self, params: dict[str, object]) -> None:
        """Build the tower set from ``start``, ``state`` or a seeded random one."""
        if "grippers" in params and "robots" in params:
            raise ManagementException(f"{self.name}: give grippers or robots, not both")
        grippers = params.get("grippers", params.get("robots", 1))
        if not isinstance(grippers, int) or grippers < 1:
            raise ManagementException(f"{self.name}: grippers (robots) must be at least 1, "
                                      f"got {grippers}")
        self.grippers = grippers
        self.on = initial_towers(self.name, params, self.home)

    def initial_entities(self) -> dict[str, str]:
        """One ``gripper``, or ``gripper1`` ... ``gripperN``."""
        if self.grippers == 1:
            return {"gripper": self.default_entity_type}
        names = [f"gripper{index}" for index in range(1, self.grippers + 1)]
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
