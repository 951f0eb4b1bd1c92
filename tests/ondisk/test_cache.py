"""ondisk.cache: the user's cache folder, and reading back only files no other account could
have written (a cached pickle runs code when it is loaded)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from ondisk.cache import cache_folder, make_cache_folder, read_own

NOBODY = 65534


def _own_file(tmp_path: Path, data: bytes = b"tables") -> Path:
    folder = tmp_path / "goalagent"
    make_cache_folder(folder)
    path = folder / "cached"
    path.write_bytes(data)
    path.chmod(0o644)
    return path


def test_the_folder_follows_xdg_cache_home_and_falls_back_to_the_home_cache(monkeypatch,
                                                                           tmp_path):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert cache_folder() == tmp_path / "goalagent"
    monkeypatch.setenv("XDG_CACHE_HOME", "")  # empty counts as unset (XDG base directories)
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert cache_folder() == tmp_path / "home" / ".cache" / "goalagent"


def test_a_new_folder_is_the_users_alone(tmp_path):
    folder = tmp_path / "a" / "goalagent"
    make_cache_folder(folder)
    assert folder.stat().st_mode & 0o777 == 0o700 & ~_umask()


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def test_the_users_own_file_is_read(tmp_path):
    assert read_own(_own_file(tmp_path, b"saved"), 100) == b"saved"


def test_a_missing_file_or_folder_is_none(tmp_path):
    assert read_own(tmp_path / "nothing" / "here", 100) is None


@pytest.mark.parametrize("mode", [0o664, 0o646])
def test_a_file_others_may_write_is_not_read(tmp_path, mode):
    path = _own_file(tmp_path)
    path.chmod(mode)
    assert read_own(path, 100) is None


@pytest.mark.parametrize("mode", [0o770, 0o777])
def test_a_file_in_a_folder_others_may_write_is_not_read(tmp_path, mode):
    path = _own_file(tmp_path)
    path.parent.chmod(mode)
    assert read_own(path, 100) is None


@pytest.mark.skipif(os.geteuid() != 0, reason="giving a file away needs root")
@pytest.mark.parametrize("whose", ["file", "folder"])
def test_a_file_or_folder_of_another_account_is_not_read(tmp_path, whose):
    path = _own_file(tmp_path)
    os.chown(path if whose == "file" else path.parent, NOBODY, NOBODY)
    assert read_own(path, 100) is None


def test_a_link_a_larger_file_or_a_folder_is_not_read(tmp_path):
    path = _own_file(tmp_path, b"x" * 101)
    assert read_own(path, 100) is None
    link = path.parent / "link"
    small = _own_file(tmp_path / "other", b"small")
    link.symlink_to(small)
    assert read_own(small, 100) == b"small"
    assert read_own(link, 100) is None
    assert read_own(path.parent, 100) is None
