"""One writer per folder: a second command on a locked folder stops with exit 2 naming the
holder; a lock left by a killed process is taken over; campaigns started twice at once."""

import errno
import json
import os
import signal
import socket
import subprocess
import sys
import time

import pytest

from mbds.errors import ModelError
from mbds.io.lock import LOCK_FILE, folder_lock, holder
from tests.campaign.models import two_mass


def test_the_lock_is_held_inside_the_block_and_released_after(tmp_path):
    with folder_lock(tmp_path, "test"):
        info = holder(tmp_path)
        assert info["pid"] == os.getpid() and info["host"] == socket.gethostname() and info["command"] == "test"
        with pytest.raises(ModelError) as caught, folder_lock(tmp_path, "second"):
            pass
        assert f"process {os.getpid()}" in str(caught.value) and "test is working on this folder" in str(caught.value)
    assert holder(tmp_path) is None


def test_a_lock_left_by_a_killed_process_is_taken_over(tmp_path):
    code = f"from mbds.io.lock import folder_lock; import time\nwith folder_lock({str(tmp_path)!r}, 'sleeper'):\n    time.sleep(60)"
    sleeper = subprocess.Popen([sys.executable, "-c", code])
    deadline = time.monotonic() + 30
    while holder(tmp_path) is None and time.monotonic() < deadline:
        time.sleep(0.05)
    assert holder(tmp_path)["pid"] == sleeper.pid
    with pytest.raises(ModelError):  # alive: not taken
        with folder_lock(tmp_path, "test"):
            pass
    sleeper.send_signal(signal.SIGKILL)
    sleeper.wait()
    assert holder(tmp_path)["pid"] == sleeper.pid  # the stale lock is still there
    with folder_lock(tmp_path, "test"):
        assert holder(tmp_path)["pid"] == os.getpid()


def test_a_process_killed_while_taking_the_lock_leaves_no_lock(tmp_path):
    """Killed (SIGKILL) after writing what the lock holds and before it appears: no lock is left,
    only a hidden file beside it, and the next command takes the lock. (A lock created empty and
    then written could be left empty: unreadable, it was never taken over.)"""
    code = ("import os, signal\nos.link = lambda *args: os.kill(os.getpid(), signal.SIGKILL)\n"
            f"from mbds.io.lock import folder_lock\nwith folder_lock({str(tmp_path)!r}, 'killed'):\n    pass")
    killed = subprocess.Popen([sys.executable, "-c", code])
    assert killed.wait() == -signal.SIGKILL
    assert holder(tmp_path) is None
    assert [p.name for p in tmp_path.iterdir()] == [f"{LOCK_FILE}.{socket.gethostname()}.{killed.pid}.tmp"]
    with folder_lock(tmp_path, "test"):
        assert holder(tmp_path)["command"] == "test"


def test_a_file_system_without_hard_links_still_gets_a_whole_lock(tmp_path, monkeypatch):
    """Where os.link is refused (EPERM, as on some network file systems), the lock is created
    exclusively and written in place; a second command still finds it."""
    def refused(source, target):
        raise PermissionError(errno.EPERM, "hard links not supported", str(target))

    monkeypatch.setattr(os, "link", refused)
    with folder_lock(tmp_path, "first"):
        assert holder(tmp_path)["command"] == "first"
        assert [p.name for p in tmp_path.iterdir()] == [LOCK_FILE]
        with pytest.raises(ModelError), folder_lock(tmp_path, "second"):
            pass
    assert holder(tmp_path) is None


def test_a_lock_of_another_host_is_never_taken_over(tmp_path):
    (tmp_path / LOCK_FILE).write_text(json.dumps({"host": "elsewhere", "pid": 1, "start": "x", "command": "mbds job"}))
    with pytest.raises(ModelError) as caught, folder_lock(tmp_path, "test"):
        pass
    assert "on elsewhere" in str(caught.value) and f"remove {tmp_path / LOCK_FILE}" in str(caught.value)


def test_two_campaigns_started_at_once(tmp_path):
    """The second `mbds-campaign run` of one job exits 2 and names the first; the first
    completes every task."""
    job = two_mass(tmp_path, "c'gravity = 9.81, 5\nworld.breakTime = 0.3\n", jobs="000-001")
    command = [sys.executable, "-m", "mbds.cli.campaign", "run", str(job)]
    first = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
    lock = job.parent / "campaign" / LOCK_FILE
    deadline = time.monotonic() + 120
    while not lock.exists() and time.monotonic() < deadline:
        time.sleep(0.05)
    first.send_signal(signal.SIGSTOP)  # hold the first at work while the second starts
    try:
        second = subprocess.run(command, capture_output=True, text=True, timeout=120)
    finally:
        first.send_signal(signal.SIGCONT)
    _, first_err = first.communicate(timeout=300)
    assert first.returncode == 0, first_err
    # outside a terminal, the scheduling process writes its phases and a line per task
    assert "warm-up: 1 distinct model(s) ready" in first_err and "running 10 of 10 tasks on 1 worker(s)" in first_err
    assert "task v00/prepare done in" in first_err and "(10/10)" in first_err
    assert second.returncode == 2, second.stderr
    assert f"mbds-campaign run is working on this folder: process {first.pid}" in second.stderr
    assert not lock.exists()


def test_mbds_run_and_mbds_job_refuse_a_locked_folder(tmp_path):
    from typer.testing import CliRunner

    from mbds.cli.main import app
    from mbds.simulation.versions import ensure_version
    from tests.examples import copy_example

    folder = copy_example("2mass", tmp_path / "2mass")
    ensure_version(folder, 0, folder / "2mass.wld")
    with folder_lock(folder / "000", "mbds run"):
        result = CliRunner().invoke(app, ["run", str(folder / "000")])
        assert result.exit_code == 2 and "mbds run is working on this folder" in result.stderr
    with folder_lock(folder, "mbds job"):
        result = CliRunner().invoke(app, ["job", str(folder / "2mass.job")])
        assert result.exit_code == 2 and "mbds job is working on this folder" in result.stderr
