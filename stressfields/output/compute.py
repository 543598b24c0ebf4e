"""Computing a dataset's tasks for a writer: on the local threads (returning only when no task is
still running), another local scheduler, or a dask.distributed cluster, with dask's progress bar on
stderr. Shared by every format.
"""
from __future__ import annotations

import os
import sys
from concurrent.futures import ThreadPoolExecutor
from contextlib import nullcontext

#: a sweep of at least this many points gets at least MIN_TASKS chunks where it can (`build`), and a
#: resumable part at least MIN_TASKS tasks (`parts`), so that each of two cores has work and a second
#: task to take while the first one's block is being written
PARALLEL_ABOVE = 200_000
MIN_TASKS = 4


def compute(delayed, *, progress: bool = False, scheduler=None) -> None:
    """``delayed.compute`` that, on the local threads, returns only when no task is still running: a
    failed or interrupted write must not have a thread recreate the temporary after it was removed."""
    from dask.base import get_scheduler
    from dask.threaded import get as threaded_get

    if is_client(scheduler):
        _cluster_compute(delayed, scheduler, progress)
        return
    with progress_bar(progress):
        if scheduler not in (None, "threads") or (scheduler is None and get_scheduler() not in (None, threaded_get)):
            delayed.compute(scheduler=scheduler)
            return
        workers = os.cpu_count() or 1
        pool = ThreadPoolExecutor(workers)
        try:
            delayed.compute(scheduler=threaded_get, pool=pool, num_workers=workers)
        except BaseException as exc:
            # interrupted (Ctrl-C, a signal; not a failed task): the caller removes the temporary
            # without waiting for the running tasks, one of which may wait on a lock the interrupted
            # main thread held
            pool.shutdown(wait=isinstance(exc, Exception), cancel_futures=True)
            raise
        pool.shutdown(wait=True)


def local(scheduler) -> bool:
    """Whether tasks run in this process (threads or synchronously), where a kept block is visible to
    the writer: not on a cluster, not in other processes."""
    from dask.base import get_scheduler
    from dask.local import get_sync
    from dask.threaded import get as threaded_get

    if is_client(scheduler):
        return False
    if scheduler is None:
        return get_scheduler() in (None, threaded_get, get_sync)
    return scheduler in ("threads", "threading", "sync", "synchronous", "single-threaded")


def is_client(scheduler) -> bool:
    """Whether ``scheduler`` is a dask.distributed ``Client`` (told without importing distributed)."""
    return type(scheduler).__name__ == "Client" and type(scheduler).__module__.startswith("distributed")


def _cluster_compute(delayed, client, progress: bool) -> None:
    """Compute on a dask.distributed cluster; with ``progress``, dask.distributed's text progress bar of
    the tasks done on the workers (to stderr, like the run's other lines), blocking until the end."""
    future = client.compute(delayed)
    try:
        if progress:
            from contextlib import redirect_stdout

            from distributed import progress as show

            with redirect_stdout(sys.stderr):     # the bar prints to stdout; stdout carries results only
                show(future, notebook=False, multi=False)
            print(file=sys.stderr)
        future.result()
    finally:
        try:
            future.release()
        except Exception:       # a lost scheduler has released it already
            pass


def progress_bar(show: bool):
    """dask's progress bar, on stderr: stdout carries results only (`run -o x.nc > log` stays empty)."""
    if not show:
        return nullcontext()
    from dask.diagnostics import ProgressBar

    return ProgressBar(minimum=0.5, dt=0.2, out=sys.stderr)
