"""Files written whole, and output paths checked before any work is done.

Every file the package writes goes through :func:`atomic_write`: the content is
written to a temporary file in the destination's folder and renamed over the
destination only when complete, so an interrupted run leaves either the old file
or the new one, never a truncated one.  :func:`check_output_file` and
:func:`check_output_dir` refuse, in one line, a path that could not be written,
before the computation whose result would otherwise be lost.
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
import stat
import tempfile

from ..problem.errors import FileError
from ..problem.validation import InputError

__all__ = ["WriteError", "atomic_path", "atomic_write", "check_output_dir", "check_output_file"]

#: Longest file name most file systems accept.
NAME_MAX = 255


class WriteError(FileError):
    """A file could not be written (a full disk, a folder in the way, a place where
    nothing can be created): one line naming the file and the system's reason.

    Parameters
    ----------
    path : str
        The file; without ``exc``, the whole message (so that the error survives a
        trip from a worker process, as every :class:`InputError` does).
    exc : OSError, optional
        What the system said.
    """

    def __init__(self, path, exc=None, *, parameters=()):
        reason = f" ({exc.strerror or type(exc).__name__})" if isinstance(exc, OSError) else ""
        message = path if exc is None else f"could not write {path}{reason}"
        super().__init__(message, parameters=parameters)


def _destination(path: str) -> str:
    """Where writing ``path`` lands: the file a symbolic link names (so that the link
    stays a link, as writing through it would leave it), else ``path``."""
    return os.path.realpath(path) if os.path.islink(path) else path


def _special(path: str) -> str | None:
    """What ``path`` is when it exists and is neither a regular file nor a folder
    (``"a device"``, ``"a FIFO"``, ``"a socket"``), following symbolic links; else None.
    A file renamed over it would replace it: ``/dev/null`` would become a file."""
    try:
        mode = os.stat(path).st_mode
    except OSError:  # absent, or a dangling link: a file is made there
        return None
    if stat.S_ISREG(mode) or stat.S_ISDIR(mode):
        return None
    if stat.S_ISFIFO(mode):
        return "a FIFO"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "a device"


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextlib.contextmanager
def atomic_path(path, folder=False):
    """A temporary path beside ``path``, renamed to ``path`` when the block succeeds.

    For writers that take a path rather than a file object (NetCDF, Zarr).

    Parameters
    ----------
    path : str or os.PathLike
    folder : bool
        Yield a new folder (a Zarr store) rather than a file; an existing folder at
        ``path`` is replaced.

    Yields
    ------
    str
        The temporary path (same extension as ``path``); on an exception (or an
        interrupt) it is removed and ``path`` is left as it was.

    Raises
    ------
    WriteError
        The system's refusal, or ``path`` is a device, FIFO or socket.  A symbolic
        link to a file is kept: the file it names is replaced (a folder is replaced
        where it is).
    """
    shown = os.fspath(path)
    # A file is written through a link; a folder (a Zarr store) is not: the tree a link
    # names is not removed to replace it.
    path = shown if folder else _destination(shown)
    special = _special(path)
    if special:
        raise WriteError(f"could not write {shown} (it is {special}, not a file)")
    parent = os.path.dirname(os.path.abspath(path))
    suffix = "-" + os.path.basename(path)[:64]
    try:
        if folder:
            tmp = tempfile.mkdtemp(prefix=".tmp-", suffix=suffix, dir=parent)
        else:
            fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=suffix, dir=parent)
            os.close(fd)
        # Ordinary permissions, not the temporary's private ones.
        os.chmod(tmp, (0o777 if folder else 0o666) & ~_umask())
    except OSError as exc:
        raise WriteError(shown, exc) from None
    try:
        yield tmp
        if folder and os.path.isdir(path):
            shutil.rmtree(path)
        os.replace(tmp, path)
    except BaseException as exc:
        if folder:
            shutil.rmtree(tmp, ignore_errors=True)
        else:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        if isinstance(exc, OSError):
            raise WriteError(shown, exc) from None
        raise


@contextlib.contextmanager
def atomic_write(path, mode="w", **kwargs):
    """Open a temporary file beside ``path``; on success rename it to ``path``.

    Parameters
    ----------
    path : str or os.PathLike
    mode : {"w", "wb"}
    **kwargs
        Passed to :func:`open` (e.g. ``newline=""``).

    Yields
    ------
    file object
        The temporary file; on an exception (or an interrupt) it is removed and
        ``path`` is left as it was.
    """
    with atomic_path(path) as tmp, open(tmp, mode, **kwargs) as fh:
        yield fh
        fh.flush()
        os.fsync(fh.fileno())


def _check_name(option: str, path: str):
    if not path:
        raise InputError(f"{option} must be a path, got ''")
    for part in path.replace(os.sep, "/").split("/"):
        if len(part.encode()) > NAME_MAX:
            raise InputError(f"{option} must have names of at most {NAME_MAX} bytes, "
                             f"got one of {len(part.encode())}")


def _check_folder(option: str, folder: str, path: str):
    folder = folder or "."
    if not os.path.exists(folder):
        raise InputError(f"{option} must be in an existing folder, got {path!r} "
                         f"({folder!r} does not exist)")
    if not os.path.isdir(folder):
        raise InputError(f"{option} must be in a folder, got {path!r} ({folder!r} is a file)")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError(f"{option} must be in a writable folder, got {path!r}")
    _probe(option, folder, path)


def _probe(option: str, folder: str, path: str):
    """Create and remove a file in ``folder``: ``os.access`` answers yes for root even
    where nothing can be created (``/proc``, ``/sys``, a read-only mount)."""
    try:
        fd, tmp = tempfile.mkstemp(prefix=".tmp-probe-", dir=folder)
    except OSError as exc:
        raise InputError(f"{option} must be in a writable folder, got {path!r} "
                         f"({exc.strerror or type(exc).__name__})") from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(tmp)


def check_output_file(option: str, path, suffixes=None) -> str:
    """``path`` if a file can be written there (``suffixes``: the allowed extensions).

    Raises
    ------
    InputError
        Empty, a folder, a device, FIFO or socket (which the file renamed over it
        would replace), in a missing or read-only folder or under a file, a name
        too long, or an extension not in ``suffixes``.  A symbolic link is checked,
        and later written, as the file it names.
    """
    path = os.fspath(path) if path is not None else ""
    _check_name(option, path)
    if os.path.isdir(path):
        raise InputError(f"{option} must be a file, got the folder {path!r}")
    special = _special(path)
    if special:
        raise InputError(f"{option} must be a regular file, got {path!r} ({special})")
    if suffixes is not None:
        ext = os.path.splitext(path)[1].lower()
        if ext not in suffixes:
            raise InputError(f"{option} must end in one of {', '.join(suffixes)}, got {path!r}")
    # Written through a symbolic link: the checks are of the file it names (a loop of
    # links names none).
    if os.path.islink(path):
        try:
            os.stat(path)
        except OSError as exc:
            if exc.errno == errno.ELOOP:
                raise InputError(f"{option} must not be a loop of symbolic links, got "
                                 f"{path!r}") from None
    target = _destination(path)
    _check_folder(option, os.path.dirname(target), path)
    if os.path.exists(target) and not os.access(target, os.W_OK):
        raise InputError(f"{option} must be a writable file, got {path!r}")
    return path


def check_output_dir(option: str, path) -> str:
    """``path`` if it is, or can be created as, a writable folder (its parent must exist)."""
    path = os.fspath(path) if path is not None else ""
    _check_name(option, path)
    if os.path.exists(path):
        if not os.path.isdir(path):
            raise InputError(f"{option} must be a folder, got the file {path!r}")
        if not os.access(path, os.W_OK | os.X_OK):
            raise InputError(f"{option} must be a writable folder, got {path!r}")
        _probe(option, path, path)
        return path
    _check_folder(option, os.path.dirname(os.path.normpath(path)), path)
    return path
