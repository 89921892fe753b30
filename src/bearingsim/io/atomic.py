"""Atomic writers: an output file is either complete or absent (write to a temporary file
beside it, then rename), and output locations checked before any work.

- :func:`check_output` — refuse, in one line, a destination that cannot be written (under
  ``/proc`` or ``/sys``, a parent that is a file, no permission, a read-only file system, a
  directory or a device where a file is expected), before anything is computed.
- :func:`atomic_path` / :func:`atomic_open` / :func:`write_json` — the writers.

Temporary files are named ``.<name>.tmp-<host>-<pid>-<start>-<token><suffix>`` beside the
output: the writing process (host, process id and start time) is in the name, so that the next
write to the same place removes the temporaries of a writer that is gone (killed, say), and never
those of a writer still running (two processes, or two threads, may write the same file at once:
each has its own temporary and the last rename wins). Files are created with the mode the umask
gives (``0o666 & ~umask``), as ``open`` would, and any failure removes the temporary file.
"""

from __future__ import annotations

import contextlib
import errno
import json
import os
import re
import secrets
import socket
import stat
import time
import zlib
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

from ..errors import ConfigError
from .jsonable import to_jsonable

__all__ = [
    "LEGACY_TEMP_AGE_S",
    "atomic_open",
    "atomic_path",
    "check_output",
    "clean_stale_temporaries",
    "storage_reason",
    "write_json",
]

#: kernel file systems that hold no user files; an output under them is refused
_VIRTUAL = (Path("/proc"), Path("/sys"))

#: age [s] after which a temporary of the former naming (``tempfile.mkstemp``: no process in the
#: name, bearingsim < 0.3) is taken as left by a killed run: a running writer touches its
#: temporary while writing, and writes only after its computation, so one hour is generous
LEGACY_TEMP_AGE_S = 3600.0

#: errors of a writer inside :func:`atomic_path` that are about the output's storage (full,
#: over quota, too large, read-only); they become the one-line :class:`ConfigError` (other
#: errors pass unchanged, the temporary still removed)
_STORAGE_ERRNOS = frozenset({errno.ENOSPC, errno.EDQUOT, errno.EFBIG, errno.EROFS})

_TEMP = re.compile(r"tmp-(?P<host>[0-9a-f]{8})-(?P<pid>\d+)-(?P<start>\d+)-[0-9a-f]{8}(\.\w+)?")
_LEGACY = re.compile(r"[a-z0-9_]{8}\.\w{1,8}")


def _host_tag() -> str:
    """The host in temporary names (CRC-32 of the host name): on a file system shared by several
    machines, a writer judges only the temporaries of its own machine."""
    return f"{zlib.crc32(socket.gethostname().encode()):08x}"


def _proc_stat(pid: int) -> tuple[str, int] | None:
    """State letter and start time [clock ticks since boot] of process ``pid`` from
    ``/proc/<pid>/stat`` (proc(5), fields 3 and 22); ``None`` where there is no ``/proc``."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            raw = fh.read()
    except OSError:
        return None
    fields = raw[raw.rfind(b")") + 2 :].split()  # the command name may hold blanks and ')'
    try:
        return fields[0].decode(), int(fields[19])
    except (IndexError, ValueError):
        return None


def _start_time(pid: int) -> int:
    st = _proc_stat(pid)
    return 0 if st is None else st[1]


def _alive(pid: int, start: int) -> bool:
    """Whether the writer ``pid`` that started at ``start`` (0: unknown) may still be writing.
    A zombie or a process id reused by a later process counts as gone; in doubt, alive."""
    if os.name == "nt":  # os.kill(pid, 0) would terminate the process there
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        pass  # exists, owned by another user (EPERM), or cannot tell: keep its files
    st = _proc_stat(pid)
    if st is None:
        return True
    state, started = st
    return state != "Z" and not (start and started != start)


def clean_stale_temporaries(path: str | Path) -> list[Path]:
    """Remove the temporaries that writers of ``path`` left when they were killed; returns them.

    A temporary of this machine whose writer process is gone (or is a zombie, or whose process id
    now belongs to a later process) is removed; one of a running writer is kept. Temporaries of
    the former naming (no process in the name) are removed when untouched for
    :data:`LEGACY_TEMP_AGE_S`. Best effort: a directory that cannot be listed is left alone.

    Parameters
    ----------
    path : str or Path
        The output file whose temporaries to look for (beside it).
    """
    dest = Path(path)
    prefix = f".{dest.name}."
    host = _host_tag()
    removed: list[Path] = []
    try:
        entries = list(os.scandir(dest.parent))
    except OSError:
        return removed
    now = time.time()
    for entry in entries:
        name = entry.name
        if not name.startswith(prefix):
            continue
        rest = name[len(prefix) :]
        m = _TEMP.fullmatch(rest)
        try:
            if m:
                if m["host"] != host or _alive(int(m["pid"]), int(m["start"])):
                    continue
            elif not (
                _LEGACY.fullmatch(rest)
                and entry.is_file(follow_symlinks=False)
                and now - entry.stat(follow_symlinks=False).st_mtime > LEGACY_TEMP_AGE_S
            ):
                continue
            os.unlink(entry.path)
            removed.append(Path(entry.path))
        except OSError:
            continue  # gone meanwhile (another writer cleaned it) or not ours to remove
    return removed


def _temp_name(dest: Path, suffix: str) -> str:
    return (
        f".{dest.name}.tmp-{_host_tag()}-{os.getpid()}-{_start_time(os.getpid())}-"
        f"{secrets.token_hex(4)}{suffix}"
    )


def _kind(mode: int) -> str:
    for test, what in (
        (stat.S_ISDIR, "a directory"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
        (stat.S_ISFIFO, "a named pipe"),
        (stat.S_ISSOCK, "a socket"),
    ):
        if test(mode):
            return what
    return "not a regular file"


def _stat(p: Path) -> os.stat_result | None | OSError:
    """``os.stat(p)``; ``None`` when nothing is there (or a component is a file); the error when
    it cannot be looked at (no search permission, a symbolic-link loop)."""
    try:
        return os.stat(p)
    except (FileNotFoundError, NotADirectoryError):
        return None
    except OSError as exc:
        return exc


def _reason(exc: OSError, where: Path) -> str:
    e = exc.errno
    if e in (errno.EACCES, errno.EPERM):
        return f"permission denied in {str(where)!r}"
    if e == errno.EROFS:
        return f"{str(where)!r} is on a read-only file system"
    if e in (errno.ENOSPC, errno.EDQUOT):
        return f"no space left in {str(where)!r} ({exc.strerror})"
    return f"{exc.strerror or type(exc).__name__} in {str(where)!r}"


def _unwritable(dest: Path, directory: bool) -> str | None:
    """Why ``dest`` cannot be written, or ``None`` when it can (:func:`check_output`)."""
    full = Path(os.path.abspath(dest))
    for v in _VIRTUAL:
        if full == v or v in full.parents:
            return f"it is under {v}, a virtual file system of the kernel"
    st = _stat(full)
    if isinstance(st, OSError):
        return _reason(st, full)
    if st is not None:
        if directory and not stat.S_ISDIR(st.st_mode):
            return "it is a file, not a directory"
        if not directory and not stat.S_ISREG(st.st_mode):
            return f"it is {_kind(st.st_mode)}, not a regular file"
    # the nearest existing folder: the output is created in it (missing folders first)
    base = full if (directory and st is not None) else full.parent
    while True:
        bst = _stat(base)
        if isinstance(bst, OSError):
            return _reason(bst, base)
        if bst is not None:
            break
        base = base.parent
    if not stat.S_ISDIR(bst.st_mode):
        return f"{str(base)!r} is a file, not a directory"
    if base == full:  # an existing output directory (a sweep store in use): look, never write
        if os.access(full, os.W_OK | os.X_OK):
            return None
        ro = hasattr(os, "statvfs") and os.statvfs(full).f_flag & os.ST_RDONLY
        return _reason(OSError(errno.EROFS if ro else errno.EACCES, ""), full)
    probe = base / _temp_name(Path(full.name or "out"), ".probe")
    try:
        fd = os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_CLOEXEC, 0o600)
    except OSError as exc:
        return _reason(exc, base)
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(probe)
    return None


def storage_reason(exc: BaseException, dest: str | Path) -> str | None:
    """Why the output at ``dest`` could not be written when ``exc`` is an error of its
    storage (full, over quota, too large, read-only; e.g. "no space left in ..."), else
    ``None``."""
    if not isinstance(exc, OSError) or exc.errno not in _STORAGE_ERRNOS:
        return None
    return _reason(exc, Path(exc.filename).parent if isinstance(exc.filename, str) else Path(dest))


def _error(
    field: str, dest: str | Path, reason: str, directory: bool, valid: str | None = None
) -> ConfigError:
    valid = valid or (
        "a directory that can be created or written"
        if directory
        else "a regular file in a writable directory"
    )
    return ConfigError(f"{field} = {str(dest)!r} cannot be written: {reason}; valid: {valid}")


def check_output(path: str | Path, field: str, *, directory: bool = False) -> Path:
    """Refuse in one line an output location that cannot be written; returns ``Path(path)``.

    Called before any work (the CLI, for every output option), so that a run never fails at its
    end for want of a place to write. Refused: a path under ``/proc`` or ``/sys``; a path through
    a file (a parent that is a file); a folder without write permission or on a read-only file
    system (probed by creating and removing an empty file, named after the output, in the
    nearest existing folder; an existing output directory, which may be a sweep store in use, is
    only looked at with ``os.access``); a directory, device or pipe where a file is expected
    (``directory=False``), a file where a directory is (``directory=True``). Missing folders are
    fine: the writers create them.

    Parameters
    ----------
    path : str or Path
        The output file (or directory).
    field : str
        The option or argument named in the message (``"-o/--output"``, ``"--plot"``).
    directory : bool
        Whether the output is a directory (``reproduce -o``, ``sweep run -o``).
    """
    if not str(path):
        raise _error(field, path, "the path is empty", directory)
    dest = Path(path)
    reason = _unwritable(dest, directory)
    if reason is not None:
        raise _error(field, dest, reason, directory)
    return dest


def _missing_dirs(folder: Path) -> list[Path]:
    """The folders from ``folder`` upwards that do not exist yet (deepest first)."""
    out = []
    while _stat(folder) is None and folder != folder.parent:
        out.append(folder)
        folder = folder.parent
    return out


@contextlib.contextmanager
def atomic_path(
    path: str | Path, suffix: str | None = None, *, field: str = "path"
) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success rename it onto ``path`` (onto its
    target when ``path`` is a symbolic link: the link stays and points to the new content).

    Nothing is left at ``path`` if the block raises (no half-written output): the temporary
    file, and the folders created for it, are removed on any failure. The stale temporaries of
    killed writers of ``path`` are removed first (:func:`clean_stale_temporaries`). The
    temporary is created with the umask's mode. A destination that cannot be written, and an
    error of the storage while writing (full, read-only), raise a one-line
    :class:`ConfigError` naming ``field``.

    Parameters
    ----------
    path : str or Path
        The output file.
    suffix : str, optional
        Suffix of the temporary file (default: the output's, else ``.tmp``); some writers choose
        the format by it.
    field : str
        Name of the output in error messages.
    """
    dest = Path(path)
    if dest.is_symlink():  # written through the link: its target gets the new content (the
        dest = Path(os.path.realpath(dest))  # rename replaced the link, the target kept the old)
    st = _stat(dest)
    if isinstance(st, os.stat_result) and not stat.S_ISREG(st.st_mode):
        raise _error(field, dest, f"it is {_kind(st.st_mode)}, not a regular file", False)
    created = _missing_dirs(dest.parent)
    try:
        dest.parent.mkdir(parents=True, exist_ok=True)
        clean_stale_temporaries(dest)
        for _ in range(100):
            tmp = dest.parent / _temp_name(dest, suffix or dest.suffix or ".tmp")
            try:
                fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_CLOEXEC, 0o666)
                break
            except FileExistsError:
                continue
        else:  # pragma: no cover - 100 collisions of 32 random bits
            raise FileExistsError(errno.EEXIST, "no free temporary name", str(dest.parent))
    except OSError as exc:
        _remove_dirs(created)
        reason = _unwritable(dest, False) or _reason(exc, dest.parent)
        raise _error(field, dest, reason, False) from None
    os.close(fd)
    try:
        try:
            yield tmp
        except OSError as exc:
            if exc.errno not in _STORAGE_ERRNOS:
                raise
            full = exc.errno != errno.EROFS  # full, over quota, too large: not the folder's fault
            raise _error(
                field,
                dest,
                _reason(exc, dest.parent),
                False,
                valid="free space there, or another path" if full else None,
            ) from None
        try:
            os.replace(tmp, dest)
        except OSError as exc:
            reason = _unwritable(dest, False) or _reason(exc, dest.parent)
            raise _error(field, dest, reason, False) from None
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        _remove_dirs(created)
        raise


def _remove_dirs(created: list[Path]) -> None:
    """Remove the folders an unsuccessful write created (deepest first; only empty ones)."""
    for d in created:
        try:
            d.rmdir()
        except OSError:
            return


@contextlib.contextmanager
def atomic_open(
    path: str | Path, mode: str = "w", *, field: str = "path", **kw: Any
) -> Iterator[IO[Any]]:
    """Open a temporary file beside ``path`` and rename it onto ``path`` on success
    (:func:`atomic_path`)."""
    with atomic_path(path, field=field) as tmp, open(tmp, mode, **kw) as fh:
        yield fh


def write_json(path: str | Path, obj: Any, *, field: str = "path") -> None:
    """Write ``obj`` as indented JSON atomically."""
    with atomic_open(path, "w", field=field, encoding="utf-8") as fh:
        json.dump(to_jsonable(obj), fh, indent=2)
        fh.write("\n")
