"""The atomic-write machinery every format shares: nothing appears under a target's name until it
is complete, and what a killed run leaves is cleared by the next.

Files beside a target are named after it and after the process that made them, so a later run can
tell its own from those of a run that is gone (`clean_stale`):

    .NAME.HOST-PID.RANDOM.tmp        a file being written (NetCDF)
    .NAME.HOST-PID.RANDOM.partial    a folder being written (a Zarr store, a report folder)
    .NAME.lock                       the run lock (`target_lock`), naming its owner
    NAME.parts/                      the parts of an interrupted resumable run (`parts_dir`)

A format writes its temporary (`temporary`), then publishes it (`publish` for a file,
`publish_folder` for a folder); `removed_on_failure` removes the temporary on any failure and
says an I/O failure in one line (`output_error`).
"""
from __future__ import annotations

import hashlib
import os
import re
import shutil
import socket
import tempfile
import time
from contextlib import contextmanager
from pathlib import Path

from ..errors import OutputError, name_problem

#: host and process that own a temporary: a short hash of the host name (a shared disk may be written
#: from several machines, whose process ids mean nothing here) and the process id
OWNER = f"{hashlib.sha256(socket.gethostname().encode()).hexdigest()[:6]}-{os.getpid()}"
#: bytes a temporary's name adds to the target's (the longest process id of Linux, 4194304)
TEMP_OVERHEAD = len(".." + OWNER.split("-")[0] + "-4194304" + ".12345678" + ".partial")


def folder_of(target: Path) -> Path:
    """The folder a target is written in (``.`` for a bare name)."""
    return target.parent if str(target.parent) else Path(".")


def temporary(target: Path, suffix: str) -> Path:
    """A new, unique, empty temporary beside ``target``: a file (``.tmp``) or a directory (``.partial``)."""
    parent = folder_of(target)
    prefix = f".{target.name}.{OWNER}."
    try:
        if suffix == ".partial":
            return Path(tempfile.mkdtemp(prefix=prefix, suffix=suffix, dir=parent))
        fd, tmp = tempfile.mkstemp(prefix=prefix, suffix=suffix, dir=parent)
    except OSError as exc:
        raise OutputError(f"cannot write {target}: {exc.strerror or exc}") from None
    os.close(fd)
    return Path(tmp)


def clean_stale(target: Path) -> list[Path]:
    """Remove the temporaries of ``target`` left by killed runs of this host (their process is gone);
    those of live runs, or of other hosts, are kept. Returns what was removed."""
    parent = folder_of(target)
    pattern = re.compile(rf"^\.{re.escape(target.name)}\.([0-9a-f]{{6}})-(\d+)\.[^./]+\.(tmp|partial)$")
    removed = []
    try:
        names = os.listdir(parent)
    except OSError:
        return removed
    for name in names:
        m = pattern.match(name)
        if m and f"{m[1]}-{m[2]}" != OWNER and not owner_alive(f"{m[1]}-{m[2]}"):
            path = parent / name
            shutil.rmtree(path, ignore_errors=True) if path.is_dir() else remove(path)
            removed.append(path)
    return removed


def owner_alive(owner: str) -> bool:
    """Whether the process ``HOST-PID`` may still run (always True for another host)."""
    host, _, pid = owner.partition("-")
    if host != OWNER.split("-")[0] or not pid.isdigit():
        return True
    try:
        os.kill(int(pid), 0)
    except ProcessLookupError:
        return False
    except OSError:         # exists, owned by someone else
        return True
    return True


def publish(tmp: Path, target: Path, overwrite: bool) -> None:
    """Give the complete file ``tmp`` its final name. Without ``overwrite`` the target is claimed in one
    atomic step (a hard link fails if the name exists), so of two runs onto one name exactly one wins."""
    if overwrite:
        os.replace(tmp, target)
        return
    try:
        os.link(tmp, target, follow_symlinks=False)
    except FileExistsError:
        raise OutputError(f"{target} was created by another run while this one was writing; refusing to "
                          "overwrite it (use --overwrite)") from None
    except OSError:         # no hard links on this file system: the run lock (`target_lock`) guards the name
        if os.path.lexists(target):
            raise OutputError(f"{target} exists; refusing to overwrite it (use --overwrite)") from None
        os.rename(tmp, target)
        return
    os.unlink(tmp)


def publish_folder(partial: Path, target: Path, overwrite: bool) -> None:
    """Rename the complete folder (a store, `comparison.publish_report`'s report) onto ``target``. A
    rename replaces an empty directory, so the name is checked first, under the run lock. The folder
    replaced by ``overwrite`` is moved aside in one rename and removed after: the target is always
    either the old folder or the new one."""
    if not os.path.lexists(target):
        os.rename(partial, target)
        return
    if not overwrite:
        raise OutputError(f"{target} was created by another run while this one was writing; refusing to "
                          "overwrite it (use --overwrite)")
    old = temporary(target, ".partial")
    os.rename(target, old) if target.is_dir() and not target.is_symlink() else os.replace(target, old / "old")
    os.rename(partial, target)
    shutil.rmtree(old, ignore_errors=True)


class removed_on_failure:
    """Remove the temporary ``tmp`` of ``target`` if the block fails in any way (an interrupt
    included), and report I/O failures as one OutputError naming the target and the free space."""

    def __init__(self, tmp, target: Path):
        self.tmp, self.target = str(tmp), target

    def __enter__(self):
        return self

    def __exit__(self, kind, exc, tb):
        if kind is None:
            return False
        remove(self.tmp)
        error = output_error(exc, self.target, folder_of(self.target))
        if error is not None:
            raise error from exc
        return False


def output_error(exc: BaseException, target: Path, folder: Path) -> OutputError | None:
    """The one-line OutputError for an I/O failure while writing ``target`` (naming the free space
    in ``folder``), or None for anything else (an OutputError already is one)."""
    if isinstance(exc, OSError) and not isinstance(exc, OutputError):
        return OutputError(f"cannot write {target}: {exc.strerror or exc}{_space(folder)}")
    if isinstance(exc, RuntimeError) and str(exc).startswith("NetCDF:"):   # HDF5's I/O failures
        return OutputError(f"cannot write {target}: {exc}{_space(folder)}")
    return None


def check_name(target: Path, folder: Path) -> None:
    """The target's name is UTF-8 text without NUL (`errors.name_problem`: the NetCDF library takes
    UTF-8 names) and leaves room for its temporaries (`TEMP_OVERHEAD` bytes more)."""
    why = name_problem(str(target))
    if why is not None:
        raise OutputError(f"cannot write {ascii(str(target))}: {why}")
    try:
        limit = os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError):
        limit = 255
    size = len(os.fsencode(target.name))
    if size + TEMP_OVERHEAD > limit:
        raise OutputError(f"cannot write {target}: its name is {size} bytes; at most "
                          f"{limit - TEMP_OVERHEAD} here (file names are limited to {limit} bytes and "
                          f"the temporary written first adds {TEMP_OVERHEAD})")


def parts_dir(target: Path) -> Path:
    """Where the finished parts of an interrupted run wait (see `parts`)."""
    return target.with_name(target.name + ".parts")


@contextmanager
def target_lock(target: Path):
    """Hold ``.NAME.lock`` beside ``target`` for a whole run: a second run onto the same target stops
    before computing anything. The lock names its owner (`OWNER`); a lock whose process is gone
    (a killed run) is taken over."""
    lock = target.with_name(f".{target.name}.lock")
    for _ in range(3):
        try:
            fd = os.open(lock, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
        except FileExistsError:
            owner = _read_lock(lock)
            if owner == "":
                continue
            if owner is None or owner_alive(owner):
                raise OutputError(f"{target} is being written by another run (process {owner or '?'}; "
                                  f"lock {lock}); wait for it, or remove the lock if that run is gone") from None
            remove(lock)
            continue
        except OSError as exc:
            raise OutputError(f"cannot write {target}: {exc.strerror or exc}") from None
        with os.fdopen(fd, "w") as fh:
            fh.write(OWNER)
        break
    else:
        raise OutputError(f"{target}: cannot take the lock {lock}")
    try:
        yield
    finally:
        remove(lock)


def _read_lock(lock: Path) -> str | None:
    for _ in range(20):            # a new lock is empty until its owner writes its name (microseconds)
        try:
            owner = lock.read_text().strip()
        except FileNotFoundError:
            return ""              # released meanwhile: take it
        except OSError:
            return None
        if owner:
            return owner
        time.sleep(0.005)
    return None


def umask() -> int:
    """The process's umask, read without changing it (os.umask sets it): what a published file's or
    folder's mode leaves out, since mkstemp and mkdtemp make them private (0600, 0700)."""
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    return 0o022


def fsync_path(path: str | os.PathLike) -> None:
    """Make a file's contents (or a folder's names) durable."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _space(folder: Path) -> str:
    try:
        st = os.statvfs(folder)
    except OSError:
        return ""
    return f" ({st.f_bavail * st.f_frsize / 1e6:,.1f} MB free in {folder})"


def remove(path: str | os.PathLike) -> None:
    """Unlink ``path``; gone already is fine."""
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass
