"""Replacing a file atomically: a reader, a crash, kill -9 or a power cut sees the old file or
the new one, whole, never a mixture or a half.

The new content goes to a temporary file in the target's folder; it is flushed and fsynced,
renamed over the target with ``os.replace`` (atomic on POSIX), then the folder is fsynced so
the rename itself is on disk.

The mode is set explicitly, and the process umask is never read or changed (changing it, even
for an instant, races every other thread that creates a file). An existing file keeps its
permission bits (set-id bits are dropped: new content must not inherit them). A new file gets
what a plain ``open()`` would give: the temporary file is created with mode 0o666 and the kernel
takes the umask (and a folder's default ACL) off, exactly as for any other new file.

Targets: an existing target must be a regular file. A folder, device (``/dev/full``), FIFO or
socket is refused, never replaced. A symbolic link is refused too: writing through it would
let a link planted where a save lands redirect the save onto any file the user may write, and
replacing the link would silently undo a link the user made on purpose. The message names
where the link points, so the user can give that path instead.
"""

from __future__ import annotations

import contextlib
import errno
import os
import secrets
import stat
from collections.abc import Iterator
from pathlib import Path
from types import TracebackType
from typing import IO

_CLOEXEC = getattr(os, "O_CLOEXEC", 0)
_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_DIRECTORY = getattr(os, "O_DIRECTORY", 0)
_NAME_KEPT = 200
"""Characters of the target's name kept in the temporary name (NAME_MAX is 255)."""


class TargetError(OSError):
    """A path a save must not replace (not a regular file, or a symbolic link), or a folder
    in which no file can be made."""


def file_kind(mode: int) -> str:
    """What a file that is not regular is, in words (from its ``st_mode``)."""
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISFIFO(mode):
        return "a FIFO"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "a special file"


def check_target(path: str | os.PathLike[str]) -> Path:
    """``path`` if a save may replace it: missing, or a regular file (not a link). Its folder
    is created when missing. Raises :class:`TargetError` saying why not."""
    target = Path(path)
    try:
        info = os.lstat(target)
    except (FileNotFoundError, NotADirectoryError):  # the folder is made (or refused) below
        info = None
    if info is not None and stat.S_ISLNK(info.st_mode):
        raise TargetError(f"{path} is a symbolic link (to {os.readlink(target)}): a save "
                          "neither writes through a link nor replaces it; give the file's "
                          "own path")
    if info is not None and not stat.S_ISREG(info.st_mode):
        raise TargetError(f"{path} exists and is not a regular file")
    folder = target.parent
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise TargetError(f"cannot create the folder {folder}: {error.strerror or error}") from None
    if not os.access(folder, os.W_OK | os.X_OK):
        raise TargetError(f"cannot write in the folder {folder}")
    return target


class AtomicFile:
    """A file being written under a temporary name beside ``path``; :meth:`commit` puts it in
    place, :meth:`discard` (or leaving a ``with`` block by an exception) removes it.

    ``binary`` chooses bytes or text (``encoding``) for :meth:`write`."""

    def __init__(self, path: str | os.PathLike[str], *, binary: bool = False,
                 encoding: str = "utf-8") -> None:
        self.path = check_target(path)
        existing = _existing_mode(self.path)
        self._temporary, self._stream = _create_temporary(self.path, binary=binary,
                                                          encoding=encoding)
        self._done = False
        if existing is not None:
            try:
                os.fchmod(self._stream.fileno(), existing)
            except BaseException:
                self.discard()
                raise

    def write(self, data: str | bytes) -> int:
        """Append ``data`` to the new content."""
        return self._stream.write(data)

    def commit(self) -> Path:
        """Flush and fsync the new content, put it in place of ``path`` and fsync the
        folder; the target is checked again first (it may have changed meanwhile)."""
        if self._done:
            raise ValueError(f"{self.path}: this atomic file was already closed")
        try:
            self._stream.flush()
            os.fsync(self._stream.fileno())
            self._stream.close()
            check_target(self.path)
            os.replace(self._temporary, self.path)
        except BaseException:
            self.discard()
            raise
        self._done = True
        _fsync_folder(self.path.parent)
        return self.path

    def discard(self) -> None:
        """Drop the new content; ``path`` stays as it was."""
        if self._done:
            return
        self._done = True
        # Neither step raises: discarding runs while another exception (a failed write, a
        # signal's stop) is on its way out, and must not replace it.
        with contextlib.suppress(OSError):  # first: a signal may cut what follows
            Path(self._temporary).unlink(missing_ok=True)
        with contextlib.suppress(OSError):  # a write that failed (disk full) fails again
            self._stream.close()

    def __enter__(self) -> AtomicFile:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        if kind is None:
            self.commit()
        else:
            self.discard()


def write_atomically(path: str | os.PathLike[str], data: str | bytes, *,
                     encoding: str = "utf-8") -> Path:
    """Replace ``path`` by ``data`` (text in ``encoding``, or bytes), all or nothing."""
    with AtomicFile(path, binary=isinstance(data, bytes), encoding=encoding) as file:
        file.write(data)
    return file.path


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """For a writer that wants a file name rather than a stream (ffmpeg writing a video): a
    new, empty file beside ``path``, with the same suffix (writers choose their format by it),
    for the block to write by name. When the block ends well it is fsynced, given the mode
    (as :class:`AtomicFile` does) and put in place of ``path``; when it raises, it is removed
    and ``path`` stays as it was."""
    target = check_target(path)
    existing = _existing_mode(target)
    temporary, created = _create_temporary(target, suffix=target.suffix)
    created.close()
    try:
        yield Path(temporary)
        fd = os.open(temporary, os.O_RDONLY | _CLOEXEC | _NOFOLLOW)
        try:
            os.fsync(fd)
            if existing is not None:
                os.fchmod(fd, existing)
        finally:
            os.close(fd)
        check_target(target)
        os.replace(temporary, target)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    _fsync_folder(target.parent)


def _existing_mode(target: Path) -> int | None:
    """The permission bits of the file at ``target`` (None: there is none yet)."""
    try:
        return stat.S_IMODE(os.stat(target, follow_symlinks=False).st_mode) & 0o777
    except FileNotFoundError:
        return None


def _create_temporary(target: Path, suffix: str = ".tmp", *, binary: bool = True,
                      encoding: str = "utf-8") -> tuple[str, IO]:
    """A new, empty file beside ``target`` under an unused hidden name ending in ``suffix``,
    open for writing: (name, stream).

    ``open(name, "x")`` makes the file and its stream in one C call (mode 0o666 less the
    umask, close-on-exec, and no link followed: O_EXCL refuses any existing name). A
    descriptor from ``os.open`` handed to ``os.fdopen`` by Python code could be closed twice
    when a signal handler's exception (the run's Ctrl-C) lands between the two: the
    second close then hits whatever file has taken the number since."""
    while True:
        name = target.parent / f".{target.name[:_NAME_KEPT]}.{secrets.token_hex(4)}{suffix}"
        try:
            if binary:
                return str(name), open(name, "xb")  # noqa: SIM115 - the caller closes it
            return str(name), open(name, "x", encoding=encoding, newline="")  # noqa: SIM115
        except FileExistsError:
            continue


def _fsync_folder(folder: Path) -> None:
    """Make a rename in ``folder`` durable (a file system that cannot sync a folder, such as
    some network ones, answers EINVAL: there is nothing more to do there)."""
    fd = os.open(folder, os.O_RDONLY | _DIRECTORY | _CLOEXEC)
    try:
        os.fsync(fd)
    except OSError as error:
        if error.errno not in (errno.EINVAL, errno.ENOTSUP):
            raise
    finally:
        os.close(fd)
