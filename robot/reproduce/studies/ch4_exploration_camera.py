"""``ch4-exploration-camera``: ``ch4-exploration`` with s_o measured on rendered frames of the
``close`` camera (OpenCV, eq. 4.19) instead of ground truth; same configurations, statistics
and plots."""

from __future__ import annotations

from robot.reproduce.framework import Study
from robot.reproduce.studies import ch4_exploration
from robot.reproduce.studies.common.ch4 import Perception, ScaledExplorationConfig


class CameraConfig(ScaledExplorationConfig):
    """``ch4-exploration``'s parameters, s_o from the camera."""

    perception: Perception = "camera"


STUDY = Study(
    name="ch4-exploration-camera",
    description="ch4-exploration with s_o from rendered close-camera frames (thesis Figs 4.4-4.9)",
    config=CameraConfig, result=ch4_exploration.Exploration, run=ch4_exploration.run,
    metrics=ch4_exploration.metrics, claims=ch4_exploration.claims,
    figures=ch4_exploration.figures,
    notes=ch4_exploration.notes("here measured on each rendered 320×240 frame (the dark "
                                "region's bounding box, OpenCV)"),
    listings=ch4_exploration.variant_listing, quick={"scale": 0.05}, default_seeds=5,
    deviations=ch4_exploration.STUDY.deviations,
    headline=ch4_exploration.STUDY.headline,
)
