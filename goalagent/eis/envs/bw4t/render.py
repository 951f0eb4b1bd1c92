"""A picture of the BW4T world (matplotlib): rooms, corridors, doors, blocks, robots, and the
colour sequence with the next colour to deliver marked. y grows downwards, as in BW4T."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from goalagent.eis.envs.bw4t.world import World

COLOURS = {
    "RED": "#d62728", "ORANGE": "#ff7f0e", "YELLOW": "#e8d21d", "GREEN": "#2ca02c",
    "BLUE": "#1f77b4", "PINK": "#f48fb1", "WHITE": "#ffffff", "DARK_GRAY": "#555555",
}
ZONE_FILL = {"ROOM": "#e8e8e8", "CORRIDOR": "#fbfbf4", "CHARGINGZONE": "#d9f2d9",
             "BLOCKADE": "#a04040"}


def draw_world(figure: object, world: World, round_number: int) -> None:
    """Fill ``figure`` (a matplotlib ``Figure``) with the world as it is now."""
    from matplotlib.patches import Circle, Rectangle

    axes = figure.add_subplot(1, 1, 1)
    for zone in world.zones:
        r = zone.rect
        fill = "#c8c8d8" if zone is world.drop_zone else ZONE_FILL[zone.kind]
        axes.add_patch(Rectangle((r.x, r.y), r.width, r.height, facecolor=fill,
                                 edgecolor="#333333" if zone.is_room else "#bbbbbb"))
        axes.text(r.x + 0.3, r.y + 0.3, zone.name, fontsize=6, va="top", color="#555555")
    for door in world.doors:
        r = door.rect
        open_ = world.occupier(door.room) is None
        axes.add_patch(Rectangle((r.x, r.y), r.width, r.height,
                                 facecolor="#5c5" if open_ else "#c33", edgecolor="none"))
    for block in world.blocks:
        if block.placed and block.holder is None:
            r = block.rect
            axes.add_patch(Rectangle((r.x, r.y), r.width, r.height,
                                     facecolor=COLOURS[block.colour], edgecolor="black", lw=0.5))
    for robot in world.robots:
        axes.add_patch(Circle((robot.x, robot.y), robot.size / 2, facecolor="#333333",
                              edgecolor="red" if robot.collided else "black"))
        if robot.holding:
            top = robot.holding[-1]
            axes.add_patch(Rectangle((robot.x - 0.4, robot.y - 0.4), 0.8, 0.8,
                                     facecolor=COLOURS[top.colour], edgecolor="black", lw=0.5))
        axes.text(robot.x, robot.y - robot.size / 2 - 0.3, robot.name, fontsize=6, ha="center")
    _draw_sequence(axes, world)
    axes.set_xlim(0, world.spec.width)
    axes.set_ylim(world.spec.height + 3, 0)
    axes.set_aspect("equal")
    axes.set_axis_off()
    done = f"{world.sequence_index}/{len(world.sequence)}"
    axes.set_title(f"BW4T {world.spec.name}  round {round_number}  delivered {done}", fontsize=9)


def _draw_sequence(axes: object, world: World) -> None:
    """The sequence as a strip of squares under the map; the next colour is outlined."""
    from matplotlib.patches import Rectangle

    y = world.spec.height + 1
    for index, colour in enumerate(world.sequence):
        next_one = index == world.sequence_index
        axes.add_patch(Rectangle((1 + 1.5 * index, y), 1.2, 1.2, facecolor=COLOURS[colour],
                                 edgecolor="black", lw=2 if next_one else 0.5,
                                 alpha=0.35 if index < world.sequence_index else 1.0))
