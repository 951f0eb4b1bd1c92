"""ondisk.cache: the one place that says where the user's cache folder is."""

from __future__ import annotations

from ondisk.cache import cache_folder
from robot.paths import default_model_path
from robot.reproduce.framework.cache import default_folder


def test_the_folder_follows_xdg_cache_home_and_falls_back_to_the_home_cache(monkeypatch,
                                                                           tmp_path):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert cache_folder() == tmp_path / "goalagent"
    assert default_model_path().parent == default_folder().parent == tmp_path / "goalagent"
    monkeypatch.setenv("XDG_CACHE_HOME", "")  # empty counts as unset (XDG base directories)
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert cache_folder() == tmp_path / "home" / ".cache" / "goalagent"
    assert default_folder() == tmp_path / "home" / ".cache" / "goalagent" / "reproduce"
