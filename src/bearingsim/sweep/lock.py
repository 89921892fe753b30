"""The client lock of a sweep dataset: one client writes a dataset at a time.

The lock is the file ``DATASET/records/.lock``, one JSON object naming its holder::

    {"host": "node7", "pid": 4242, "start": 853437, "boot_id": "6286e4a7-...",
     "token": "<uuid4 hex>", "created_utc": "2026-11-23T16:00:00Z", "bearingsim": "0.2.0"}

``start`` is the holder's start time (``/proc/<pid>/stat`` field 22, clock ticks since boot) and
``boot_id`` the kernel's ``/proc/sys/kernel/random/boot_id``: together with ``host`` and ``pid``
they name one process of one boot of one machine, so a reused PID is recognised. ``token`` tells
two holders in one process apart. The file is written completely under a temporary name and
then hard-linked onto ``.lock`` (``os.link`` fails when the name exists: atomic, also on NFS), so
a lock is never seen half-written; on a file system without hard links it is created with
``O_EXCL`` and written at once. While held, a thread refreshes the file's modification time every
:data:`LOCK_REFRESH_S`.

A lock is *stale*, and is taken over, when

- it is empty or not a JSON object and at least :data:`LOCK_EMPTY_GRACE_S` old (a client killed
  between creating and writing it: older versions created the file first and wrote it after);
- it names this machine (same host name and boot id) and its process is gone, or its PID now
  belongs to a process started at another time (PID reuse);
- it names another machine (or this host before a reboot), whose processes cannot be seen from
  here, and was not refreshed for :data:`LOCK_STALE_S`. Ages are measured on the file system's
  own clock (the modification time of a file written just before), not this host's, so clock skew
  between the machines does not matter; the holder refreshes every :data:`LOCK_REFRESH_S`, ten
  times within the stale age, which also covers NFS attribute caching (``acregmax``, 60 s by
  default). A holder frozen longer than that (a suspended machine) loses its lock: its heartbeat
  notices (:attr:`ClientLock.lost`) and its sweep stops.

Clients decide one at a time: a client looks at the lock, judges it and creates or takes it over
while holding ``flock`` on ``records/.lock.mutex`` (an empty file that stays; the kernel releases
the ``flock`` of a killed process, so this mutex is never stale; Linux NFS clients map it onto
NFS byte-range locks, which the server shares between machines). Without it, several clients
judging the same stale lock at once could each remove the lock another had just taken. Where
the file system has no locks (``flock`` fails) the decision is not serialized; a stale lock is
then renamed to a private name first and checked to be the file judged stale (same inode and
modification time), and linked back otherwise, which narrows the race to microseconds. Even two
holders would keep every committed run intact (runs own their chunks; at worst a run is
computed twice).
"""

from __future__ import annotations

import contextlib
import glob
import json
import os
import shutil
import socket
import threading
import time
import uuid as uuidlib
from pathlib import Path
from typing import Any

from .._version import __version__
from ..errors import ConfigError

__all__ = [
    "ClientLock",
    "client_lock",
    "judge_lock",
    "CREATION_LOCKLESS_S",
    "LOCK_EMPTY_GRACE_S",
    "LOCK_NAME",
    "LOCK_REFRESH_S",
    "LOCK_STALE_S",
    "LOCK_TEMP_PREFIX",
    "MUTEX_NAME",
    "remove_stale_creations",
    "this_process",
]

#: lock file of the client running a sweep on the dataset (inside the dataset)
LOCK_NAME = "records/.lock"
#: prefix of the lock's temporary files in ``records/`` (removed by ``remove_stale_temporaries``)
LOCK_TEMP_PREFIX = ".lock-"
#: the holder refreshes the lock's modification time this often [s]
LOCK_REFRESH_S = 30.0
#: a lock of another machine not refreshed for this long is stale [s]
LOCK_STALE_S = 300.0
#: an empty or unreadable lock is stale once this old [s]; it is waited for while younger
LOCK_EMPTY_GRACE_S = 2.0
#: a dataset creation's temporary directory without a lock is stale once this old [s]: the
#: lock is written milliseconds after the directory (exploratory testing, twenty-seventh
#: session: a Ctrl-C during creation left a lockless ``.NAME.creating-*`` in 5 of 9 tries,
#: zarr's background writes re-creating files after the cleanup; at 300 s a rerun kept it)
CREATION_LOCKLESS_S = 30.0
#: attempts to take the lock when other clients keep changing it
_ATTEMPTS = 20
#: the mutex that serializes the clients' decisions (``flock``), beside the lock
MUTEX_NAME = "records/.lock.mutex"
#: longest wait for the mutex (held for milliseconds, or up to LOCK_EMPTY_GRACE_S) [s]
MUTEX_WAIT_S = 10.0


def _boot_id() -> str | None:
    try:
        with open("/proc/sys/kernel/random/boot_id", encoding="ascii") as fh:
            return fh.read().strip() or None
    except (OSError, ValueError):
        return None


def _proc_start(pid: int) -> int | None:
    """Start time of process ``pid`` [clock ticks since boot] (``None``: unknown here)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as fh:
            stat = fh.read()
        # field 2 (the command) may hold spaces and parentheses: count from the last ')'
        return int(stat[stat.rindex(b")") + 2 :].split()[19])
    except (OSError, ValueError, IndexError):
        return None


def this_process() -> dict[str, Any]:
    """Identity of the calling process: ``host``, ``pid``, ``start`` [clock ticks since boot]
    and ``boot_id`` (the last two ``None`` where ``/proc`` does not have them)."""
    pid = os.getpid()
    return {
        "host": socket.gethostname(),
        "pid": pid,
        "start": _proc_start(pid),
        "boot_id": _boot_id(),
    }


def _pid_alive(pid: int) -> bool:
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    except OverflowError:
        return False
    return True


def _int_or_none(v: Any) -> int | None:
    return v if isinstance(v, int) and not isinstance(v, bool) else None


def judge_lock(
    owner: dict[str, Any] | None, age_s: float, me: dict[str, Any] | None = None
) -> tuple[bool | None, str]:
    """Whether a lock is stale (see the module docstring).

    Parameters
    ----------
    owner : dict or None
        The lock's JSON object (``None``: empty or not a JSON object).
    age_s : float
        Time since the lock was last written or refreshed [s].
    me : dict, optional
        :func:`this_process` (default: the calling process).

    Returns
    -------
    stale : bool or None
        ``True`` stale, ``False`` held by a live client, ``None`` empty but young (being
        written: wait).
    why : str
        Why, in words (for messages).
    """
    me = this_process() if me is None else me
    if owner is None:
        if age_s >= LOCK_EMPTY_GRACE_S:
            return True, f"left empty or unreadable {age_s:.0f} s ago"
        return None, "being written"
    pid = _int_or_none(owner.get("pid"))
    same_machine = owner.get("host") == me["host"] and owner.get("boot_id") in (
        None,
        me["boot_id"],
    )
    if same_machine and pid is not None:
        if not _pid_alive(pid):
            return True, f"process {pid} is gone"
        start = _int_or_none(owner.get("start"))
        now_start = _proc_start(pid)
        if start is not None and now_start is not None and start != now_start:
            return True, f"process {pid} is gone (the PID now belongs to another process)"
        return False, "a running process of this host"
    if age_s >= LOCK_STALE_S:
        return True, f"not refreshed for {age_s:.0f} s (stale after {LOCK_STALE_S:.0f} s)"
    # a lock of this machine without a readable PID is judged by age too (it was called "a
    # lock of another host"; exploratory testing, twenty-seventh session)
    whose = "a lock without a readable PID" if same_machine else "a lock of another host"
    return False, (
        f"refreshed {max(age_s, 0.0):.0f} s ago; {whose} is taken over once it "
        f"has not been refreshed for {LOCK_STALE_S:.0f} s"
    )


def _read_owner(path: Path) -> dict[str, Any] | None:
    """The lock's JSON object, ``None`` when empty or not a JSON object; raises ``OSError``."""
    with open(path, "rb") as fh:
        raw = fh.read(65536)
    try:
        owner = json.loads(raw.decode("utf-8"))
    except ValueError:
        return None
    return owner if isinstance(owner, dict) else None


class ClientLock:
    """The lock ``DATASET/records/.lock`` of one sweep client (see the module docstring).

    Parameters
    ----------
    dataset : str or Path
        The dataset directory.

    Attributes
    ----------
    owner : dict
        What this client writes into the lock (:func:`this_process` and a ``token``).
    held : bool
        Whether this client holds the lock now.
    lost : dict or None
        The lock's content when the heartbeat found another client's lock in its place (this
        client was frozen longer than :data:`LOCK_STALE_S` and was taken over).
    """

    def __init__(self, dataset: str | Path) -> None:
        self.dataset = Path(dataset)
        self.path = self.dataset / LOCK_NAME
        self.owner = {
            **this_process(),
            "token": uuidlib.uuid4().hex,
            "created_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
            "bearingsim": __version__,
        }
        self.held = False
        self.lost: dict[str, Any] | None = None
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    # ------------------------------------------------------------------ taking the lock
    def _content(self) -> bytes:
        return json.dumps(self.owner).encode()

    def write_into(self, dataset: str | Path) -> None:
        """Write the lock into a dataset not yet published (the temporary directory of
        :func:`~bearingsim.sweep.store.create_dataset`): renamed into place, the dataset is
        locked from its first instant. :meth:`adopt` after the rename."""
        p = Path(dataset) / LOCK_NAME
        p.parent.mkdir(parents=True, exist_ok=True)
        fd = os.open(p, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
        with os.fdopen(fd, "wb") as fh:
            fh.write(self._content())

    def adopt(self) -> None:
        """Hold the lock written by :meth:`write_into` (the dataset is now in place)."""
        self.held = True
        self._start_heartbeat()

    def _in_use(self, owner: dict[str, Any] | None, why: str) -> ConfigError:
        who = f"{owner.get('host')}:{owner.get('pid')}" if owner else "another client"
        return ConfigError(
            f"dataset = {str(self.dataset)!r} is in use by the sweep client {who} ({why}; lock "
            f"{str(self.path)!r}); wait for it to finish, or delete the lock if that client is gone"
        )

    def acquire(self) -> None:
        """Take the lock: create it, or take a stale one over; a live one raises
        :class:`ConfigError` naming its holder."""
        if self.held:
            return
        if not self.path.parent.is_dir():
            raise ConfigError(
                f"dataset = {str(self.dataset)!r} is not a bearingsim sweep dataset (no "
                f"{str(self.path.parent)!r} directory)"
            )
        tmp = self.path.parent / f"{LOCK_TEMP_PREFIX}{self.owner['token']}"
        try:
            with self._mutex():
                self._decide(tmp)
        except OSError as exc:  # e.g. a dataset this user cannot write
            raise ConfigError(
                f"dataset = {str(self.dataset)!r}: the lock {str(self.path)!r} cannot be written "
                f"({exc.strerror}); valid: a dataset directory this user can write"
            ) from None
        finally:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        self._start_heartbeat()

    @contextlib.contextmanager
    def _mutex(self):
        """Hold ``flock`` on :data:`MUTEX_NAME` (nothing where the file system has no locks)."""
        try:
            import fcntl
        except ImportError:  # not POSIX
            yield
            return
        try:
            fd = os.open(self.dataset / MUTEX_NAME, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError:  # e.g. read-only: creating the lock fails next, with its message
            yield
            return
        try:
            deadline = time.monotonic() + MUTEX_WAIT_S
            while True:
                try:
                    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    break
                except BlockingIOError:
                    if time.monotonic() > deadline:
                        raise ConfigError(
                            f"dataset = {str(self.dataset)!r}: another client held "
                            f"{str(self.dataset / MUTEX_NAME)!r} for {MUTEX_WAIT_S:g} s while "
                            "taking the lock; try again"
                        ) from None
                    time.sleep(0.005)
                except OSError:  # no locks on this file system: see the module docstring
                    break
            yield
        finally:
            os.close(fd)  # releases the flock

    def _decide(self, tmp: Path) -> None:
        """Create the lock, or take a stale one over, or raise "in use" (under the mutex)."""
        for _ in range(_ATTEMPTS):
            self._write_tmp(tmp)
            if self._link(tmp):
                self.held = True
                return
            try:
                st = os.lstat(self.path)
                owner = _read_owner(self.path)
            except FileNotFoundError:
                continue  # released meanwhile
            except OSError as exc:
                raise ConfigError(
                    f"lock {str(self.path)!r} of dataset {str(self.dataset)!r} cannot be read "
                    f"({exc.strerror})"
                ) from None
            try:
                os.utime(tmp)  # "now" on the file system's clock
                age = os.stat(tmp).st_mtime - st.st_mtime
            except FileNotFoundError:  # tmp removed by the holder's cleaner: written again
                continue
            stale, why = judge_lock(owner, age, self.owner)
            if stale is None:  # empty and young: being written by another client
                time.sleep(min(LOCK_EMPTY_GRACE_S, max(LOCK_EMPTY_GRACE_S - age, 0.0) + 0.05))
                continue
            if not stale:
                raise self._in_use(owner, why)
            self._break(st)
        raise ConfigError(
            f"dataset = {str(self.dataset)!r}: could not take the lock {str(self.path)!r} "
            f"in {_ATTEMPTS} attempts (other clients keep taking it); try again"
        )

    def _write_tmp(self, tmp: Path) -> None:
        """The complete lock under a private name (rewritten if a cleaner removed it)."""
        with open(tmp, "wb") as fh:
            fh.write(self._content())

    def _link(self, tmp: Path) -> bool:
        """Create the lock from ``tmp`` atomically; ``False`` if a lock exists."""
        try:
            os.link(tmp, self.path)
            return True
        except FileExistsError:
            return False
        except FileNotFoundError:  # tmp removed by a cleaner: written again on the next try
            return False
        except OSError:  # no hard links here: exclusive creation, then the content at once
            try:
                fd = os.open(self.path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
            except FileExistsError:
                return False
            with os.fdopen(fd, "wb") as fh:
                fh.write(self._content())
            return True

    def _break(self, judged: os.stat_result) -> None:
        """Remove the stale lock judged from ``judged`` (and only that file)."""
        aside = self.path.parent / f"{LOCK_TEMP_PREFIX}{self.owner['token']}-stale"
        try:
            os.rename(self.path, aside)
        except FileNotFoundError:
            return  # another client removed it first
        try:
            st = os.lstat(aside)
        except FileNotFoundError:  # removed by the cleaner of a client that holds the lock now
            return
        same = (st.st_ino, st.st_dev, st.st_mtime_ns) == (
            judged.st_ino,
            judged.st_dev,
            judged.st_mtime_ns,
        )
        if not same:  # a client took the lock between our look and the rename: give it back
            with contextlib.suppress(OSError):
                os.link(aside, self.path)
        with contextlib.suppress(OSError):
            os.unlink(aside)

    # ------------------------------------------------------------------ holding it
    def _start_heartbeat(self) -> None:
        self._stop.clear()
        self._thread = threading.Thread(
            target=self._heartbeat, name="bearingsim-sweep-lock", daemon=True
        )
        self._thread.start()

    def _heartbeat(self) -> None:
        while not self._stop.wait(LOCK_REFRESH_S):
            self.refresh()

    def refresh(self) -> bool:
        """Refresh the lock's modification time; ``False`` (and :attr:`lost` set) when the
        lock is no longer this client's."""
        try:
            owner = _read_owner(self.path)
        except OSError:
            owner = None
        if owner is None or owner.get("token") != self.owner["token"]:
            self.lost = owner or {}
            self._stop.set()
            return False
        with contextlib.suppress(OSError):
            os.utime(self.path)
        return True

    def release(self) -> None:
        """Stop the heartbeat and remove the lock if it is still this client's."""
        self._stop.set()
        if self._thread is not None and self._thread is not threading.current_thread():
            self._thread.join()
        self._thread = None
        if not self.held:
            return
        self.held = False
        with contextlib.suppress(OSError):
            owner = _read_owner(self.path)
            if owner is not None and owner.get("token") == self.owner["token"]:
                os.unlink(self.path)

    def check(self) -> None:
        """Raise :class:`ConfigError` if another client took this lock over."""
        if self.lost is None:
            return
        if not self.lost:
            raise ConfigError(
                f"dataset = {str(self.dataset)!r}: the lock {str(self.path)!r} of this client was "
                "removed; stopped, committed runs are kept"
            )
        raise ConfigError(
            f"dataset = {str(self.dataset)!r}: the lock was taken over by the sweep client "
            f"{self.lost.get('host')}:{self.lost.get('pid')} (this client's lock was removed by "
            f"hand, or it was not seen for {LOCK_STALE_S:.0f} s); stopped, committed runs are "
            "kept"
        )

    def __enter__(self) -> ClientLock:
        self.acquire()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.release()


def client_lock(path: str | Path) -> ClientLock:
    """Hold ``DATASET/records/.lock`` while a sweep client writes (``with client_lock(p):``).

    A stale lock (empty, of a dead process, or of another host and not refreshed for
    :data:`LOCK_STALE_S`) is taken over; a live one is an error naming its holder.
    """
    return ClientLock(path)


def _fs_now(directory: Path) -> float:
    """The current time on the clock of the file system holding ``directory`` [s since the
    epoch] (the modification time of a file written there now; this host's clock if that
    fails)."""
    p = directory / f"{LOCK_TEMP_PREFIX}now-{uuidlib.uuid4().hex}"
    try:
        with open(p, "wb"):
            pass
        return os.stat(p).st_mtime
    except OSError:
        return time.time()
    finally:
        with contextlib.suppress(OSError):
            os.unlink(p)


def remove_stale_creations(dest: str | Path) -> int:
    """Delete the temporary directories (``.NAME.creating-*`` beside the dataset ``dest``) of
    dataset creations whose client is gone, and every ``.NAME.removing-*`` (a dataset that
    ``--force-new`` renamed aside to delete; its client was killed before the deletion ended);
    returns how many.

    A creation is judged by the lock written into it (:func:`judge_lock`); one without a lock
    (its client was killed in the first milliseconds, or a Ctrl-C's cleanup was followed by
    zarr's last background writes) by the directory's age against
    :data:`CREATION_LOCKLESS_S`. A directory renamed aside is no dataset any more (no client
    opens it), so it goes whatever its age: two clients deleting it at once both succeed.
    """
    dest = Path(dest)
    if not dest.parent.is_dir():
        return 0
    n = 0
    # the name escaped: "ds[12].zarr" is a glob class, and removed another dataset's leftovers
    # (a helper's exploratory testing, twenty-eighth session)
    name = glob.escape(dest.name)
    for d in dest.parent.glob(f".{name}.removing-*"):
        shutil.rmtree(d, ignore_errors=True)
        n += not d.exists()
    found = list(dest.parent.glob(f".{name}.creating-*"))
    if not found:
        return n
    now = _fs_now(dest.parent)
    me = this_process()
    for d in found:
        try:
            lock = d / LOCK_NAME
            if lock.exists():
                stale, _ = judge_lock(_read_owner(lock), now - lock.stat().st_mtime, me)
            else:
                stale = now - d.stat().st_mtime >= CREATION_LOCKLESS_S
        except OSError:
            continue
        if stale:
            shutil.rmtree(d, ignore_errors=True)
            n += 1
    return n
