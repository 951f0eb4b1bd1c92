"""``ch4-exploration-camera``: ``ch4-exploration`` with s_o measured on rendered frames of the
``close`` camera (OpenCV, eq. 4.19) instead of ground truth; same configurations, summary and
plots."""

from __future__ import annotations

from robot.reproduce import ch4_exploration
from robot.reproduce.framework import Progress, Reproduction


def run_seed(seed: int, scale: float, progress: Progress) -> dict:
    """One seed of ``ch4-exploration`` seen through the camera."""
    return ch4_exploration.run_seed(seed, scale, progress, perception="camera")


REPRODUCTION = Reproduction(
    name="ch4-exploration-camera",
    description="ch4-exploration with s_o from rendered close-camera frames (thesis Figs 4.4-4.9)",
    run_seed=run_seed,
    summarize=ch4_exploration.summarize,
    compare=ch4_exploration.compare,
    figures=ch4_exploration.figures,
    notes=ch4_exploration.notes("here measured on each rendered 320×240 frame (the dark "
                                "region's bounding box, OpenCV)"),
    listings=ch4_exploration.variant_listing,
    default_seeds=5,
)
