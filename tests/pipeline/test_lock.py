"""The build lock says who holds it, even when asked in the instant between the holder taking
the lock and writing its name (a race that made two concurrent makes report "another
process")."""

import fcntl
import json
import os
import threading
import time

from flumekit.pipeline.lock import build_lock


def _wait(folder, fd, holder):
    """Take the build lock of ``folder`` while ``holder`` (a thread, given the holder's open
    lock file ``fd``) runs; returns what the waiting make said."""
    said = []
    holder.start()
    try:
        with build_lock(folder, wait=30, say=said.append):
            pass
    finally:
        holder.join()
        os.close(fd)
    return said


def test_the_waiting_make_names_a_holder_that_writes_its_name_late(tmp_path):
    path = tmp_path / ".flumekit.lock"
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o666)
    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)  # held, nothing written yet

    def holder():
        time.sleep(0.3)
        os.pwrite(fd, json.dumps({"pid": 4242, "host": "lab-pc", "command": "flumekit make",
                                  "since": "2026-11-23T00:00:00Z"}).encode(), 0)
        time.sleep(0.3)
        os.ftruncate(fd, 0)
        fcntl.flock(fd, fcntl.LOCK_UN)

    said = _wait(tmp_path, fd, threading.Thread(target=holder))
    assert len(said) == 1 and "held by pid 4242 on lab-pc" in said[0], said


def test_a_holder_that_never_writes_is_another_process(tmp_path):
    fd = os.open(tmp_path / ".flumekit.lock", os.O_RDWR | os.O_CREAT, 0o666)
    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    said = _wait(tmp_path, fd, threading.Timer(1.5, lambda: fcntl.flock(fd, fcntl.LOCK_UN)))
    assert said == [f"waiting for the build lock of {tmp_path}: held by another process"]
