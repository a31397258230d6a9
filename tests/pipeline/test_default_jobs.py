"""The number of worker processes of a make without -j."""

import os

from flumekit.pipeline import executors


def _machine(monkeypatch, cpus: int, memory: int) -> None:
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: set(range(cpus)), raising=False)
    pages = {"SC_PAGE_SIZE": 4096, "SC_PHYS_PAGES": memory // 4096}
    monkeypatch.setattr(os, "sysconf", lambda name: pages[name])


def test_one_worker_per_cpu_while_memory_holds_them(monkeypatch):
    _machine(monkeypatch, cpus=2, memory=24 * 2**30)
    assert executors.default_jobs() == 2


def test_a_many_core_machine_with_little_memory_runs_fewer_workers(monkeypatch):
    # 64 CPUs, 6 GiB: at WORKER_MEMORY = 1 GiB each, six workers, not 64 that would swap
    _machine(monkeypatch, cpus=64, memory=6 * 2**30)
    assert executors.default_jobs() == 6
    _machine(monkeypatch, cpus=64, memory=2**29)  # half a GiB: still one worker
    assert executors.default_jobs() == 1
