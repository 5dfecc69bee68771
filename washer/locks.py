"""Output locks: one run at a time writes a given set of output names.

Two runs of one constants file in one folder would interleave their rows in one
b/s pair; two sweeps into one --out would race for its parts. The first run
takes the lock of the names it writes (an advisory `fcntl.flock` on a hidden
file beside them, `.NAME.lock`, which records who holds it); a second run finds
it held and stops at once with an error naming the holder, before writing
anything. The operating system drops the lock when its holder exits, even when
killed, so a stale lock never blocks a later run.

    with output_lock(folder, "ab", what="b.ab, s.ab, d.ab"):
        ...write...
"""
from __future__ import annotations

import contextlib
import datetime
import json
import os
import sys
from pathlib import Path

try:
    import fcntl
except ImportError:  # pragma: no cover - not POSIX: no locking, as before
    fcntl = None


class LockedError(RuntimeError):
    """Another run holds the output names; the message names it."""


def _holder(fd: int) -> str:
    try:
        os.lseek(fd, 0, os.SEEK_SET)
        info = json.loads(os.read(fd, 4096).decode() or "{}")
    except (OSError, ValueError):
        return "another run"
    if not info:
        return "another run"
    return (f"process {info.get('pid')} on {info.get('host')}, started {info.get('started')}: "
            f"{info.get('command')}")


@contextlib.contextmanager
def output_lock(folder, name: str, what: str = ""):
    """Hold the lock of output `name` in `folder` for the block; LockedError at once
    if another process holds it. `what` (e.g. 'b.ab, s.ab, d.ab') is for messages."""
    if fcntl is None:
        yield
        return
    folder = Path(folder)
    path = folder / f".{name}.lock"
    while True:
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0), 0o666)
        except OSError as exc:
            raise LockedError(f"{path}: cannot create the lock of {what or name} "
                              f"({exc.strerror or exc})") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = _holder(fd)
            os.close(fd)
            raise LockedError(f"{folder / (what or name)}: being written by {holder}; wait "
                              "for it to finish, or write elsewhere (another sv= name or "
                              "folder)") from None
        # The holder before us may have removed the file between our open and lock:
        # then the lock is on a name nobody else sees, so take the new file's.
        try:
            same = os.path.samestat(os.fstat(fd), os.stat(path, follow_symlinks=False))
        except OSError:
            same = False
        if same:
            break
        os.close(fd)
    try:
        info = json.dumps({
            "pid": os.getpid(), "host": os.uname().nodename,   # gethostname(2)'s name
            "started": datetime.datetime.now().isoformat(timespec="seconds"),
            "command": " ".join([Path(sys.argv[0]).name] + sys.argv[1:])[:300]}).encode()
        # Written over any stale content, then cut to its length: a truncation to 0 makes
        # ext4 write the file's data out when it is closed (its replace-by-truncate
        # heuristic), 2 to 13 ms at the end of every run even though the file is
        # unlinked by then.
        os.pwrite(fd, info, 0)
        os.ftruncate(fd, len(info))
        yield
    finally:
        with contextlib.suppress(OSError):
            os.unlink(path)              # still holding it: no one else is writing it
        os.close(fd)
