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
