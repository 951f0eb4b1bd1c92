"""A picture of the elevator building (matplotlib): one shaft per car with the car, its door
state and riders, the people waiting on each floor and the lit call buttons."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from goalagent.eis.envs.elevator.building import Building

DOOR_COLOURS = {"closed": "#555555", "opening": "#e8a33d", "opened": "#5cb85c",
                "closing": "#e8a33d"}


def draw_building(figure: object, building: Building, round_number: int) -> None:
    """Fill ``figure`` (a matplotlib ``Figure``) with the building as it is now."""
    from matplotlib.patches import Rectangle

    axes = figure.add_subplot(1, 1, 1)
    floors, cars = building.floors, len(building.cars)
    for floor in range(1, floors + 1):
        axes.axhline(floor - 1, color="#cccccc", lw=0.5)
        waiting = building.waiting(floor)
        label = f"{floor}"
        if waiting:
            label += f"  waiting {len(waiting)}"
        if building.call_up[floor]:
            label += " ^"
        if building.call_down[floor]:
            label += " v"
        axes.text(-0.2, floor - 0.5, label, ha="right", va="center", fontsize=7)
    for index, car in enumerate(building.cars):
        axes.add_patch(Rectangle((index, 0), 0.9, floors, facecolor="#f4f4f4",
                                 edgecolor="#999999"))
        level = building.height_of(car) / 10.0
        floor = building.floor_of(car)
        door = building.entrances[(floor, car.number)].door if floor is not None else "closed"
        axes.add_patch(Rectangle((index + 0.1, level + 0.05), 0.7, 0.9,
                                 facecolor=DOOR_COLOURS[door], edgecolor="black"))
        axes.text(index + 0.45, level + 0.5, f"car{car.number}\n{len(car.people)}/{car.capacity}",
                  ha="center", va="center", fontsize=6, color="white")
        if car.requested:
            axes.text(index + 0.45, floors + 0.2, " ".join(map(str, car.requested)),
                      ha="center", fontsize=6)
    arrived = sum(1 for person in building.people if person.arrived)
    axes.set_xlim(-2.5, cars + 0.2)
    axes.set_ylim(-0.2, floors + 0.7)
    axes.set_axis_off()
    seconds = building.queue.now / 1000
    axes.set_title(f"elevator  round {round_number}  t={seconds:.1f}s  arrived "
                   f"{arrived}/{len(building.people)}", fontsize=9)
