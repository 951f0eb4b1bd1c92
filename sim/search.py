"""The head-camera search world of thesis Appendix A (Fig. 7.2): find a coloured object.

A robot (a stand-in for the NAO) sits on a table; its head turns on two position-controlled
hinges, yaw about +z (positive looks left) and pitch about +y (positive looks down, as the
NAO's HeadPitch), within the NAO's limits: yaw [-2.079, 2.079], pitch [-0.67, 0.51] rad. The
head camera has the NAO's field of view (47.6 x 36.8 degrees). Each head action turns one motor
by ``HEAD_STEP`` = 0.1 rad; a move that would leave the movement boundary (App. A: [-0.5, 0.5]
in both, within the motor limits) resets the head to its resting pose (0, 0).

The target is a red cube on a thin post, placed (by the "operator") ``TARGET_DISTANCE`` m from
the head in a direction given as (yaw, pitch) like the head's: ``PLACES`` holds the two of
App. A, up-left (found in 2 looks left and 2 up) and right (3 looks right).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from sim.base import RenderedWorld
from sim.mjcf import LIGHTING, box, fmt
from sim.navigation import MARKER_RGBA

TABLE_TOP = 0.40
HEAD_POS = (0.0, 0.0, TABLE_TOP + 0.45)
"""Where the head's two axes meet (m)."""
YAW_LIMITS = (-2.079, 2.079)
PITCH_LIMITS = (-0.67, 0.51)
"""The NAO's head motor limits (rad), App. A."""
BOUNDARY = 0.5
"""The movement boundary (rad): leaving [-0.5, 0.5] in yaw or pitch resets the head (App. A)."""
HEAD_STEP = 0.1
"""How far (rad) one action turns a motor."""
CAMERA_FOVY = 36.8
"""Vertical field of view (degrees) of the NAO's camera; 320x240 frames give 47.6 horizontal."""
TARGET_DISTANCE = 1.0
TARGET_HALF = 0.025
"""Half size (m) of the red cube."""
TARGET_COLOUR = "red"
PLACES = {"up_left": (0.32, -0.285), "right": (-0.42, 0.0)}
"""Target directions (yaw, pitch in rad, as the head's) before and after it moves (App. A):
the centre ninth of the image spans +-0.146 rad of yaw and +-0.110 of pitch, the cube +-0.025,
so the cube enters it after exactly 2 looks left and 2 up, or 3 right, with 0.05 rad to spare
either side of every cell boundary."""
RGBA = {"table": "0.76 0.72 0.66 1", "floor": "0.55 0.55 0.58 1", "wall": "0.80 0.81 0.84 1",
        "robot": "0.92 0.92 0.92 1", "post": "0.50 0.50 0.52 1"}


@dataclass(frozen=True)
class SearchState:
    """Ground truth of the search world: head angles and where the target is."""

    yaw: float
    pitch: float
    target: tuple[float, float, float]
    place: tuple[float, float]


def target_position(yaw: float, pitch: float, distance: float = TARGET_DISTANCE) -> np.ndarray:
    """World position of a point ``distance`` m from the head in direction (yaw, pitch)."""
    direction = np.array([math.cos(pitch) * math.cos(yaw), math.cos(pitch) * math.sin(yaw),
                          -math.sin(pitch)])
    return np.asarray(HEAD_POS) + distance * direction


def build_mjcf() -> str:
    """The search scene as MJCF text (the target placed by ``SearchWorld.place_target``)."""
    hx, hy, hz = HEAD_POS
    post_half = 0.6
    parts = ['<mujoco model="search">',
             '<compiler angle="radian" autolimits="true"/>',
             '<option timestep="0.002" integrator="implicitfast"/>',
             LIGHTING,
             "<worldbody>",
             '<light name="top" pos="0.5 0 2.5" dir="0 0 -1" diffuse="0.45 0.45 0.45" '
             'castshadow="false"/>',
             box("floor", (0.5, 0, -0.005), (3, 3, 0.005), RGBA["floor"]),
             box("table", (0.0, 0, TABLE_TOP / 2), (0.4, 0.4, TABLE_TOP / 2), RGBA["table"]),
             box("backdrop", (2.5, 0, 1.5), (0.01, 3.0, 1.5), RGBA["wall"], collide=False),
             box("torso", (hx, hy, TABLE_TOP + 0.18), (0.05, 0.08, 0.18), RGBA["robot"]),
             f'<body name="neck" pos="{fmt(*HEAD_POS)}">',
             f'<joint name="head_yaw" type="hinge" axis="0 0 1" range="{fmt(*YAW_LIMITS)}" '
             'damping="0.5"/>',
             '<geom name="neck" type="cylinder" size="0.015 0.02" pos="0 0 -0.03" '
             f'mass="0.1" rgba="{RGBA["robot"]}" contype="0" conaffinity="0"/>',
             '<body name="head">',
             f'<joint name="head_pitch" type="hinge" axis="0 1 0" '
             f'range="{fmt(*PITCH_LIMITS)}" damping="0.5"/>',
             '<geom name="head" type="sphere" size="0.05" mass="0.4" '
             f'rgba="{RGBA["robot"]}" contype="0" conaffinity="0"/>',
             f'<camera name="head" pos="0.055 0 0" fovy="{CAMERA_FOVY}" xyaxes="0 -1 0 0 0 1"/>',
             "</body>", "</body>",
             '<body name="target" mocap="true">',
             box("target", (0, 0, 0), (TARGET_HALF,) * 3, MARKER_RGBA[TARGET_COLOUR],
                 collide=False),
             box("target_post", (0, 0, -TARGET_HALF - post_half), (0.005, 0.005, post_half),
                 RGBA["post"], collide=False),
             "</body>",
             "</worldbody>",
             "<actuator>",
             '<position name="head_yaw" joint="head_yaw" kp="20"/>',
             '<position name="head_pitch" joint="head_pitch" kp="20"/>',
             "</actuator>",
             "</mujoco>"]
    return "\n".join(parts) + "\n"


class SearchWorld(RenderedWorld):
    """The robot's pan-tilt head camera and the target cube."""

    MOVES = {"up": (0, -1), "right": (-1, 0), "down": (0, 1), "left": (1, 0)}
    """(yaw, pitch) direction of each head action (App. A: 00 up, 01 right, 10 down, 11 left)."""

    def __init__(self, place: str = "up_left", width: int = 320, height: int = 240):
        """Build the scene with the target at ``place`` and the head at rest."""
        super().__init__(build_mjcf(), width, height)
        self._yaw = self.model.joint("head_yaw").qposadr[0]
        self._pitch = self.model.joint("head_pitch").qposadr[0]
        self.place: tuple[float, float] = PLACES["up_left"]
        self.place_target(place)
        self.rest()

    def place_target(self, place: str | tuple[float, float]) -> None:
        """Put the target at a named place of ``PLACES`` or at a (yaw, pitch) direction."""
        if isinstance(place, str):
            if place not in PLACES:
                raise ValueError(f"unknown place {place!r}; known: {', '.join(PLACES)}")
            place = PLACES[place]
        self.place = (float(place[0]), float(place[1]))
        self.data.mocap_pos[0] = target_position(*self.place)
        mujoco.mj_forward(self.model, self.data)

    def rest(self) -> None:
        """Turn the head to its resting pose (0, 0) and wait until it is there."""
        self.turn_to(0.0, 0.0)

    @property
    def head(self) -> tuple[float, float]:
        """The head's current (yaw, pitch) in radians."""
        return float(self.data.qpos[self._yaw]), float(self.data.qpos[self._pitch])

    @property
    def setpoint(self) -> tuple[float, float]:
        """Where the head motors are commanded to be (yaw, pitch), on the 0.1 rad grid."""
        return float(self.data.ctrl[0]), float(self.data.ctrl[1])

    def look(self, move: str) -> bool:
        """Turn the head ``HEAD_STEP`` up, right, down or left; past the movement boundary the
        head resets to rest instead. Returns False when it was reset."""
        if move not in self.MOVES:
            raise ValueError(f"unknown head move {move!r}; use up, right, down or left")
        dyaw, dpitch = self.MOVES[move]
        yaw = round(self.setpoint[0] + dyaw * HEAD_STEP, 6)
        pitch = round(self.setpoint[1] + dpitch * HEAD_STEP, 6)
        if abs(yaw) > BOUNDARY + 1e-9 or abs(pitch) > BOUNDARY + 1e-9:
            self.rest()
            return False
        self.turn_to(yaw, pitch)
        return True

    def turn_to(self, yaw: float, pitch: float) -> None:
        """Point the head at (yaw, pitch) and step until it is still there."""
        self.data.ctrl[:] = (yaw, pitch)
        for _ in range(40):
            self.step(10)
            if (abs(self.head[0] - yaw) < 2e-3 and abs(self.head[1] - pitch) < 2e-3
                    and float(np.max(np.abs(self.data.qvel))) < 1e-2):
                return

    def state(self) -> SearchState:
        """Ground truth now."""
        yaw, pitch = self.head
        return SearchState(yaw, pitch, tuple(float(v) for v in self.data.mocap_pos[0]),
                           self.place)


if __name__ == "__main__":
    print(build_mjcf(), end="")
