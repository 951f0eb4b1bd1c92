"""Small helpers for writing MJCF text in Python: number formatting, box geoms, camera poses.

Every scene of this package is generated as text by these helpers (rather than a templating
or MJCF-builder library) because a scene is a few dozen geoms whose sizes follow from the
thesis's dimensions, which read most plainly as arithmetic next to the XML they produce.
"""

from __future__ import annotations

import math

LIGHTING = ('<visual><headlight ambient="0.45 0.45 0.45" diffuse="0.45 0.45 0.45" '
            'specular="0.05 0.05 0.05"/><quality shadowsize="0"/>'
            '<global offwidth="640" offheight="480"/></visual>')
"""Flat, shadow-free lighting: marker colours render the same wherever they are."""


def fmt(*xs: float) -> str:
    """Format numbers for an MJCF attribute."""
    return " ".join(f"{x:.5g}" for x in xs)


def box(name: str, centre: tuple[float, float, float], half: tuple[float, float, float],
        rgba: str, collide: bool = True, extra: str = "") -> str:
    """One box geom; visual-only geoms neither collide nor carry mass."""
    flags = "" if collide else ' contype="0" conaffinity="0" group="1" density="0"'
    return (f'<geom name="{name}" type="box" pos="{fmt(*centre)}" size="{fmt(*half)}" '
            f'rgba="{rgba}"{flags}{extra}/>')


def look_at(eye: tuple[float, float, float], target: tuple[float, float, float]) -> str:
    """MJCF ``xyaxes`` of a camera at ``eye`` looking at ``target`` with +z up."""
    f = [t - e for t, e in zip(target, eye, strict=True)]
    n = math.sqrt(sum(c * c for c in f))
    f = [c / n for c in f]
    right = [f[1], -f[0], 0.0]
    rn = math.hypot(right[0], right[1])
    right = [c / rn for c in right]
    up = [right[1] * f[2] - right[2] * f[1], right[2] * f[0] - right[0] * f[2],
          right[0] * f[1] - right[1] * f[0]]
    return fmt(*right, *up)
