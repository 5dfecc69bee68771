"""Safe output files: every file washer writes outside AUTO's b/s/d stream goes
through here.

A file is written under an unpredictable temporary name in its own folder
(created exclusively, so a link planted there is never followed), flushed and
fsynced, then renamed over the final name in one step and the folder synced.
Readers see the old file or the new one, never half of either; a run killed
while saving leaves at worst a hidden `.NAME.*.tmp*` file, never a truncated
NAME; a symlink at NAME is replaced by the file, its target is never opened.

    from washer.atomic import write_text, atomic_file, check_folder
    check_folder(out)                       # before any computation
    write_text(out / "report.md", text)
    with atomic_file(out / "fig.png") as fh:
        fig.savefig(fh, format="png")
"""
from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path


class OutputError(OSError):
    """An output file or folder that cannot be written; the message names it."""


def _umask() -> int:
    """The process umask, read without changing it (os.umask would, for all threads)."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("Umask:"):
                return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    return 0o022


def _fsync_folder(folder: Path) -> None:
    """Make a rename in `folder` durable (POSIX; a no-op where folders cannot be opened)."""
    try:
        fd = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def check_folder(folder, create: bool = True) -> Path:
    """`folder` exists (created if `create`) and accepts new files; OutputError
    naming it and the reason otherwise. Call before computing, not after."""
    folder = Path(folder)
    if create:
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except FileExistsError:
            raise OutputError(f"{folder}: cannot write output here: it exists and is not a "
                              "folder") from None
        except OSError as exc:
            raise OutputError(f"{folder}: cannot create the output folder "
                              f"({exc.strerror or exc})") from None
    if not folder.is_dir():
        raise OutputError(f"{folder}: cannot write output here: "
                          + ("it is not a folder" if folder.exists() else "no such folder"))
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=".washer-probe.", suffix=".tmp")
    except OSError as exc:
        raise OutputError(f"{folder}: cannot write output files in this folder "
                          f"({exc.strerror or exc})") from None
    os.close(fd)
    os.unlink(tmp)
    return folder


@contextlib.contextmanager
def atomic_file(path, text: bool = False, encoding: str = "utf-8"):
    """A file object for the new content of `path`; on a normal exit the content
    replaces `path` atomically, on an exception (KeyboardInterrupt included) the
    temporary file is removed and `path` is left as it was.

    The temporary name ends with path's suffix, so writers that choose a format
    by the name (matplotlib, numpy) see the right one."""
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=f".{path.name}.",
                                   suffix=f".tmp{path.suffix}")
    except OSError as exc:
        raise OutputError(f"{path}: cannot write this file ({exc.strerror or exc})") from None
    try:
        os.fchmod(fd, 0o666 & ~_umask())     # mkstemp's 0600 is for the temporary only
        fh = os.fdopen(fd, "w" if text else "wb", **({"encoding": encoding} if text else {}))
    except BaseException:
        os.close(fd)
        os.unlink(tmp)
        raise
    try:
        with fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)             # a link at `path` is replaced, never followed
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    _fsync_folder(folder)


def write_bytes(path, data: bytes) -> Path:
    """Replace `path` by `data` atomically (see the module docstring)."""
    with atomic_file(path) as fh:
        fh.write(data)
    return Path(path)


def write_text(path, text: str, encoding: str = "utf-8") -> Path:
    """Replace `path` by `text` atomically (see the module docstring)."""
    with atomic_file(path, text=True, encoding=encoding) as fh:
        fh.write(text)
    return Path(path)


def save_figure(fig, path, **kwargs) -> Path:
    """fig.savefig into `path` atomically, in the format its suffix names."""
    path = Path(path)
    with atomic_file(path) as fh:
        fig.savefig(fh, format=path.suffix.lstrip(".") or None, **kwargs)
    return path
