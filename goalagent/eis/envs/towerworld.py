"""The tower world of GOAL's classic tower builder: the blocks world with a gripper.

Percepts (every cycle, the whole current state): ``block(X)`` for every block, ``on(X, Y)`` for
every block not in the gripper (``Y`` a block or ``table``) and ``holding(X)`` while the gripper
holds ``X``. Actions: ``pickup(X)`` (``X`` clear and the gripper empty), ``putdown(X, Y)``
(holding ``X``; ``Y`` a clear block or ``table``) and ``nil`` (does nothing). A refused action
leaves the world unchanged.

Init parameters as for ``blocksworld``: GOAL's ``start = [2, 0, ...]`` (blocks ``b1`` ... or a
file of numbers), ``state = [on(a,b), ...]``, or ``blocks`` and ``seed`` for random towers;
``gui`` is accepted and ignored. The one entity is ``gripper`` of type ``gripper``.
"""

from __future__ import annotations

from collections.abc import Iterable

from goalagent.eis.envs.blocksworld import TABLE, initial_towers
from goalagent.eis.exceptions import ActionRefused
from goalagent.eis.pyenv import PerceptLike, PythonEnvironment, action


class TowerWorld(PythonEnvironment):
    """Blocks on a table and a gripper that picks them up and puts them down."""

    name = "towerworld"
    entity_names = ("gripper",)
    default_entity_type = "gripper"
    parameters = {"start": list | str, "gui": object, "state": list, "blocks": int,
                  "seed": int}

    def on_init(self, params: dict[str, object]) -> None:
        """Build the towers from ``state`` or a seeded random set; the gripper starts empty."""
        self.on = initial_towers(self.name, params, self.home)
        self.holding: str | None = None

    def blocks(self) -> list[str]:
        """All blocks, sorted, the held one included."""
        held = [self.holding] if self.holding is not None else []
        return sorted([*self.on, *held])

    def is_clear(self, block: str) -> bool:
        """True when ``block`` stands in the world with nothing on it (the table always)."""
        return block == TABLE or (block in self.on and block not in self.on.values())

    def percepts(self, entity: str) -> Iterable[PerceptLike]:
        """``block(X)``, ``on(X, Y)`` and ``holding(X)``, sorted."""
        result: list[PerceptLike] = [("block", block) for block in self.blocks()]
        result += [("on", block, self.on[block]) for block in sorted(self.on)]
        if self.holding is not None:
            result.append(("holding", self.holding))
        return result

    @action("pickup")
    def pickup(self, entity: str, block: str) -> None:
        """Take the clear ``block`` into the empty gripper."""
        what = f"pickup({block})"
        if self.holding is not None:
            raise ActionRefused(f"{what}: the gripper already holds {self.holding}")
        if block not in self.on:
            raise ActionRefused(f"{what}: {block} is not a block")
        if not self.is_clear(block):
            raise ActionRefused(f"{what}: {block} is not clear")
        del self.on[block]
        self.holding = block

    @action("putdown")
    def putdown(self, entity: str, block: str, target: str) -> None:
        """Put the held ``block`` on the clear block ``target`` or on the table."""
        what = f"putdown({block},{target})"
        if self.holding != block:
            held = self.holding if self.holding is not None else "nothing"
            raise ActionRefused(f"{what}: the gripper holds {held}, not {block}")
        if target == block:
            raise ActionRefused(f"{what}: a block cannot be put on itself")
        if target != TABLE and target not in self.on:
            raise ActionRefused(f"{what}: {target} is not a block on the table or a tower")
        if not self.is_clear(target):
            raise ActionRefused(f"{what}: {target} is not clear")
        self.on[block] = target
        self.holding = None

    @action("nil")
    def nil(self, entity: str) -> None:
        """Do nothing (a tower builder's idle step)."""
