"""Recording a world's camera to an mp4 as it is simulated: one job of ``GarbageWorld``.

``Recording`` is a mixin for a ``RenderedWorld`` (it uses its ``render`` and ``_camera``)
whose ``step`` calls ``_record_frame`` after every physics step: inside ``record(path)`` a
frame is captured every 1/``FRAME_RATE`` s of simulated time (imageio's ffmpeg writer), and
the file is put in place whole when the block ends (``ondisk.atomic_path``).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import mujoco

from ondisk import atomic_path

FRAME_RATE = 25.0
"""Frames per second of simulated time in recorded videos."""


class Recording:
    """Records mp4 videos of a camera while the block inside ``record`` runs (mixin)."""

    data: mujoco.MjData
    _recorder: _Recorder | None = None

    def _record_frame(self) -> None:
        """After a physics step: capture a frame if a recording is running and one is due."""
        if self._recorder is not None and self.data.time >= self._recorder.next_time:
            self._recorder.capture(self)

    def _restart_recording_clock(self) -> None:
        """Simulated time restarts (a reset): the same video goes on from the next frame."""
        if self._recorder is not None:
            self._recorder.next_time = self.data.time

    @contextmanager
    def record(self, path: str | Path, camera: str = "head") -> Iterator[Path]:
        """Record an mp4 of the ``camera`` view of everything simulated inside the block."""
        import imageio.v2 as imageio

        self._camera(camera)
        out = Path(path)
        with atomic_path(out) as partial:  # the video is put in place whole when it ends
            writer = imageio.get_writer(str(partial), fps=FRAME_RATE, macro_block_size=1)
            self._recorder = _Recorder(writer, camera, self.data.time)
            try:
                self._recorder.capture(self)
                yield out
            finally:
                self._recorder = None
                writer.close()


class _Recorder:
    """Captures a frame every 1/FRAME_RATE s of simulated time into an imageio writer."""

    def __init__(self, writer: object, camera: str, start: float):
        """Remember where frames go and when the next one is due."""
        self.writer = writer
        self.camera = camera
        self.next_time = start

    def capture(self, world: Recording) -> None:
        """Append the current frame."""
        self.writer.append_data(world.render(self.camera))  # type: ignore[attr-defined]
        self.next_time += 1.0 / FRAME_RATE
