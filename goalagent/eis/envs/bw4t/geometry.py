"""Geometry shared by the BW4T world and its robots: rectangles as Java's ``Rectangle2D``
treats them, and BW4T's way of finding a free spot for a block in a room."""

from __future__ import annotations

from dataclasses import dataclass

from goalagent.eis.envs.javarandom import JavaRandom

BLOCK_SIZE = 1.0
Point = tuple[float, float]


@dataclass(frozen=True)
class Rect:
    """An axis-aligned rectangle with ``java.awt.geom.Rectangle2D``'s half-open ``contains``."""

    x: float
    y: float
    width: float
    height: float

    @classmethod
    def centred(cls, cx: float, cy: float, width: float, height: float) -> Rect:
        return cls(cx - width / 2, cy - height / 2, width, height)

    @property
    def centre(self) -> Point:
        return (self.x + self.width / 2, self.y + self.height / 2)

    def contains(self, px: float, py: float) -> bool:
        return (self.width > 0 and self.height > 0 and self.x <= px < self.x + self.width
                and self.y <= py < self.y + self.height)

    def intersects(self, other: Rect) -> bool:
        return (self.width > 0 and self.height > 0 and other.width > 0 and other.height > 0
                and other.x + other.width > self.x and other.y + other.height > self.y
                and other.x < self.x + self.width and other.y < self.y + self.height)


def find_free_place(room: Rect, taken: list[Rect], random: JavaRandom) -> Rect:
    """A random 1x1 spot in ``room`` clear of ``taken`` (``MapUtils.findFreePlace``)."""
    tries = 100
    while True:
        x = room.x + (room.width - BLOCK_SIZE) * random.next_double()
        y = room.y + (room.height - BLOCK_SIZE) * random.next_double()
        margin = 2 * BLOCK_SIZE if tries > 0 else 0.00001
        if all(abs(bx - x) >= margin or abs(by - y) >= margin
               for bx, by in (r.centre for r in taken)):
            return Rect(x, y, BLOCK_SIZE, BLOCK_SIZE)
        tries -= 1
