"""Independent tasks on the machine's cores (toothcontact.parallel): forked processes where
no other thread runs, in order in the caller's thread where one does or where no process
can be made, and on one worker; the answers in order and alike every way, a task's error
raised to the caller."""

import os
import subprocess
import sys
import threading

import pytest

from toothcontact import parallel
from toothcontact.parallel import parallel_map, workers


def where(index):
    """The task's index squared and the process that computed it."""
    return index * index, os.getpid()


def here(index):
    """The task's index squared and the process and thread that computed it."""
    return index * index, os.getpid(), threading.get_ident()


def test_a_process_with_one_thread_may_fork():
    """A fresh interpreter (one thread, not a daemon) on this platform forks its workers."""
    found = subprocess.run([sys.executable, "-c", "from toothcontact.parallel import can_fork; "
                            "print(can_fork())"], capture_output=True, text=True, check=True)
    assert found.stdout.strip() == "True"


def test_forked_workers_answer_in_order(monkeypatch):
    """(Forced: threads an earlier test left behind, e.g. a closed Dask cluster's, would
    otherwise send the tasks to threads.)"""
    monkeypatch.setattr(parallel, "can_fork", lambda: True)
    with workers(2):
        answers = parallel_map(where, 7)
    assert [a for a, _ in answers] == [k * k for k in range(7)]
    assert os.getpid() not in {pid for _, pid in answers}


def test_tasks_run_in_order_here_while_another_thread_runs():
    """A child forked from a process with other threads could deadlock on a lock one of
    them holds: then the tasks run one after the other in this thread (threads would gain
    nothing, see the module)."""
    stop = threading.Event()
    other = threading.Thread(target=stop.wait)
    other.start()
    try:
        assert not parallel.can_fork()
        with workers(2):
            answers = parallel_map(here, 5)
    finally:
        stop.set()
        other.join()
    assert answers == [(k * k, os.getpid(), threading.get_ident()) for k in range(5)]


def test_one_worker_runs_the_tasks_in_order_here():
    seen = []
    with workers(1):
        assert parallel_map(lambda k: seen.append(k) or k, 4) == [0, 1, 2, 3]
    assert seen == [0, 1, 2, 3]


def failing(index):
    if index == 2:
        raise ValueError("task 2 cannot be answered")
    return index


@pytest.mark.parametrize("fork", [True, False])
def test_a_tasks_error_is_raised_to_the_caller(monkeypatch, fork):
    monkeypatch.setattr(parallel, "can_fork", lambda: fork)
    with workers(2), pytest.raises(ValueError, match="task 2 cannot be answered"):
        parallel_map(failing, 4)


def blas_threads() -> set[int]:
    """The thread counts of the BLAS libraries loaded (numpy's and scipy's)."""
    import numpy  # noqa: F401  (loads its BLAS)
    import scipy.linalg  # noqa: F401
    from threadpoolctl import threadpool_info

    return {pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"}


def test_blas_runs_on_the_contexts_workers_and_is_restored_after():
    from threadpoolctl import threadpool_limits

    with threadpool_limits(2, "blas"):          # as on a two-core machine, whatever this one
        assert blas_threads() == {2}
        with workers(1):
            assert blas_threads() == {1}
        with workers(4):                        # at most the threads it had
            assert blas_threads() == {2}
        assert blas_threads() == {2}


def test_a_worker_count_below_one_is_refused():
    with pytest.raises(ValueError, match="count: 0 must be an integer >= 1"):
        with workers(0):
            pass


@pytest.mark.parametrize("error", [OSError(38, "Function not implemented"),
                                   NotImplementedError("This Python build lacks "
                                                       "multiprocessing.synchronize")])
def test_tasks_run_in_order_here_where_processes_cannot_be_made(monkeypatch, error):
    """Without working semaphores (a container without /dev/shm) the pool cannot be made:
    the tasks run one after the other in this thread."""

    def no_semaphores(*args, **kwargs):
        raise error

    monkeypatch.setattr(parallel, "can_fork", lambda: True)
    monkeypatch.setattr(parallel, "ProcessPoolExecutor", no_semaphores)
    with workers(2):
        assert parallel_map(here, 3) == [(k * k, os.getpid(), threading.get_ident())
                                         for k in range(3)]


@pytest.mark.parametrize("fork", [True, False])
def test_each_answer_is_told_here_in_order_as_it_comes_back(monkeypatch, fork):
    """`done(i)` runs in the caller's process and thread, once per task, in order."""
    monkeypatch.setattr(parallel, "can_fork", lambda: fork)
    told = []
    with workers(2):
        answers = parallel_map(where, 5, done=lambda i: told.append(
            (i, os.getpid(), threading.get_ident())))
    assert [a for a, _ in answers] == [k * k for k in range(5)]
    assert told == [(k, os.getpid(), threading.get_ident()) for k in range(5)]

