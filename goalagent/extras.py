"""Which pip extra brings a Python package goalagent uses but does not install by default.

``pip install goalagent`` installs the language alone; the robot application, the mind
inspector and the pictures environments draw need extras (``pyproject.toml``). When one of
their packages is missing, the user is told the extra that brings it instead of seeing
``No module named 'mujoco'``.
"""

from __future__ import annotations

_EXTRA_OF = {
    "mujoco": "robot", "cv2": "robot", "numpy": "robot", "sklearn": "robot",
    "scipy": "robot", "yaml": "robot", "jsonschema": "robot", "fastjsonschema": "robot",
    "imageio": "robot", "imageio_ffmpeg": "robot",
    "starlette": "inspector", "uvicorn": "inspector", "websockets": "inspector",
    "matplotlib": "inspector",
}
"""Top-level module -> the extra of ``pyproject.toml`` that installs it (matplotlib is in
both robot and inspector: the smaller is named)."""


def install_hint(module: str | None) -> str | None:
    """``needs the Python package 'mujoco', which is not installed: pip install
    'goalagent[robot]'`` for a module an extra brings; None for any other."""
    top = (module or "").partition(".")[0]
    extra = _EXTRA_OF.get(top)
    if extra is None:
        return None
    return (f"needs the Python package '{top}', which is not installed: "
            f"pip install 'goalagent[{extra}]'")
