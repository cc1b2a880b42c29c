"""One writer per folder: an advisory lock file held while a command works on a folder.

``folder_lock(folder, command)`` creates ``<folder>/.mbds.lock`` atomically (a hard link), holding
the host, process id, start time (UTC, ISO 8601) and the command, and removes it when the block
ends. A second command on the same folder finds the file and stops with a :class:`ModelError`
naming the holder. A lock left by a process that no longer runs on this host (killed with
SIGKILL, say) is stale: it is taken over. A lock held from another host is never taken over,
because whether its process runs cannot be seen from here; the message says how to remove it.
"""

from __future__ import annotations

import contextlib
import errno
import json
import os
import socket
from datetime import datetime, timezone
from pathlib import Path

from mbds.errors import ModelError

LOCK_FILE = ".mbds.lock"


def holder(folder: str | Path) -> dict | None:
    """What the lock of ``folder`` says (host, pid, start, command), or None when unlocked."""
    try:
        text = (Path(folder) / LOCK_FILE).read_text(encoding="utf-8")
    except FileNotFoundError:
        return None
    try:
        info = json.loads(text)
    except json.JSONDecodeError:
        return {}  # being written this very moment, or damaged: held by someone unknown
    return info if isinstance(info, dict) else {}


def is_stale(info: dict) -> bool:
    """Whether the lock ``info`` was left by a process of this host that has ended."""
    if info.get("host") != socket.gethostname() or not isinstance(info.get("pid"), int):
        return False
    try:
        os.kill(info["pid"], 0)
    except ProcessLookupError:
        return True
    except PermissionError:  # it runs, as another user
        return False
    return False


NO_HARD_LINKS = {errno.EPERM, errno.ENOTSUP, errno.EOPNOTSUPP, errno.EXDEV, errno.EMLINK}
"""Errors of os.link on a file system that does not make hard links here."""


@contextlib.contextmanager
def folder_lock(folder: str | Path, command: str):
    """Hold the lock of ``folder`` (which must exist) while the block runs; ModelError when
    another live process holds it."""
    folder = Path(folder)
    path = folder / LOCK_FILE
    mine = {"host": socket.gethostname(), "pid": os.getpid(),
            "start": datetime.now(timezone.utc).isoformat(timespec="seconds"), "command": command}
    for _ in range(3):
        try:
            if _created(path, mine):
                break
        except FileExistsError:
            info = holder(folder)
            if info is None:  # released meanwhile
                continue
            if not is_stale(info):
                raise ModelError(_busy(info, path), folder) from None
            _take_over(path, info)
    else:
        raise ModelError(f"could not take the lock {path}: other processes keep taking it", folder)
    try:
        yield
    finally:
        if holder(folder) == mine:
            path.unlink(missing_ok=True)


def _created(path: Path, info: dict) -> bool:
    """Create the lock ``path`` holding ``info``, whole or not at all: written to a hidden file
    beside it and linked to its name (FileExistsError when a lock is there), so that a process
    killed meanwhile leaves no empty lock, which nobody could tell stale. False when that file
    was removed before the link (a run clears its folder's ``.*.tmp``): try again. On a file
    system without hard links the lock is created exclusively and written in place."""
    temporary = path.with_name(f"{path.name}.{socket.gethostname()}.{os.getpid()}.tmp")
    temporary.write_text(json.dumps(info), encoding="utf-8")
    try:
        os.link(temporary, path)
    except FileNotFoundError:
        return False
    except FileExistsError:
        raise
    except OSError as exc:
        if exc.errno not in NO_HARD_LINKS:
            raise
        with open(path, "x", encoding="utf-8") as file:
            json.dump(info, file)
    finally:
        temporary.unlink(missing_ok=True)
    return True


def _take_over(path: Path, stale: dict) -> None:
    """Remove the stale lock ``path`` unless another process replaced it meanwhile."""
    with contextlib.suppress(FileNotFoundError, json.JSONDecodeError):
        if json.loads(path.read_text(encoding="utf-8")) == stale:
            path.unlink()


def _busy(info: dict, path: Path) -> str:
    if not info:
        return f"another process is working on this folder (its lock {path} is unreadable)"
    return (f"{info.get('command', 'another command')} is working on this folder: process "
            f"{info.get('pid')} on {info.get('host')} since {info.get('start')}; wait for it to end, or, "
            f"if that process is gone, remove {path}")
