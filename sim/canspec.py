"""What a garbage can is: its mechanism, geometry and paint (``CanSpec``), the size of its
parts' colour markers and the table it stands on. Data only: ``sim.canfile`` reads cans from
YAML files, ``sim.scene`` writes the MuJoCo scene of one.
"""

from __future__ import annotations

from dataclasses import dataclass

TABLE_TOP = 0.40
"""Height of the table surface (m)."""
MARKER_SIZE: dict[str, tuple[float, float]] = {
    "body": (0.08, 0.04),
    "lid": (0.05, 0.02),
    "handle": (0.10, 0.03),
    "pedal": (0.05, 0.02),
}
"""Visible (width along y, height along z) of each part's colour marker, in metres."""

MECHANISMS: dict[str, tuple[str, str]] = {
    "push_lid": ("lid", "extend_arm"),
    "lift_handle": ("handle", "lift_up"),
    "pull_handle": ("handle", "contract_arm"),
    "slide_lid": ("lid", "sweep_left"),  # or sweep_right, see CanSpec.slide
    "pedal": ("pedal", "sweep_down"),
}
"""Each opening mechanism and the (part, action) that opens it: the can's functional pair."""


@dataclass(frozen=True)
class CanSpec:
    """Geometry, mechanism and paint of one garbage can (lengths in metres, colours RGB 0..1).

    Cans are data: ``sim.canfile`` reads them from YAML files (``sim/cans/*.yaml``).
    """

    name: str
    mechanism: str
    width: float
    depth: float
    height: float
    lid_height: float
    lid_marker_z: float
    gear: float = 0.0
    handle_drop: float = 0.13
    slide: str = "left"
    """Which way a sliding lid opens (``left`` or ``right``; slide_lid only)."""
    pedal_z: float = 0.035
    """Height of the pedal bar's centre above the table (pedal only)."""
    handle_play: tuple[str, ...] = ()
    """Axes (``x``, ``y``, ``z``) along which the handle has play: pushed that way it moves
    up to ``play_travel`` either way without opening anything (thesis Table 5.3: o2's handle
    pushed or pulled, o5's swept or lifted)."""
    play_travel: float = 0.0
    """How far (m) the handle's play lets it move each way."""
    can_slide: float = 0.0
    """How far (m) the whole can slides back on the table under a firm push (0: it stands
    fast); its parts move with it, the opening does not change (Table 5.3: o3's body, o5's
    lid)."""
    body_colour: tuple[float, float, float] = (0.80, 0.80, 0.82)
    lid_colour: tuple[float, float, float] = (0.93, 0.93, 0.90)
    source: str = ""
    """The file the can was read from (empty for a can made in code)."""

    def __post_init__(self) -> None:
        if self.mechanism not in MECHANISMS:
            raise ValueError(f"unknown mechanism {self.mechanism!r}; known: "
                             f"{', '.join(MECHANISMS)}")

    @property
    def parts(self) -> tuple[str, ...]:
        """The can's parts: body and lid, plus a handle or a pedal if the mechanism has one."""
        extra = {"lift_handle": ("handle",), "pull_handle": ("handle",), "pedal": ("pedal",)}
        return ("body", "lid", *extra.get(self.mechanism, ()))

    @property
    def functional(self) -> tuple[str, str]:
        """The (part, action) that opens the can."""
        if self.mechanism == "slide_lid":
            return "lid", f"sweep_{self.slide}"
        return MECHANISMS[self.mechanism]

    @property
    def give_joints(self) -> tuple[str, ...]:
        """The joints that let non-functional parts move (put back by ``set_opening``)."""
        slide = ("can_slide",) if self.can_slide > 0 else ()
        return slide + tuple(f"handle_play_{axis}" for axis in self.handle_play)

    @property
    def rim(self) -> float:
        """World height of the rim (top of the body walls)."""
        return TABLE_TOP + self.height

    @property
    def lid_joint(self) -> str:
        """The joint that opens the lid: a hinge, or a slide for a sliding lid."""
        return "lid_slide" if self.mechanism == "slide_lid" else "lid_hinge"

    @property
    def geared_joint(self) -> str | None:
        """The joint geared to the lid (handle or pedal slide), if any."""
        return {"lift_handle": "handle_slide", "pull_handle": "handle_slide",
                "pedal": "pedal_slide", "slide_lid": "tab_slide"}.get(self.mechanism)
