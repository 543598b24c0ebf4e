"""A bounded, thread-safe cache of per-profile set-up work, keyed by content.

A tabulated profile's set-up (the g', g'' table of an axisymmetric spline, the block trees of its
moments, the graded panel values of g') costs far more than one field point, and every call of
``generate`` and every dask chunk builds its own profile object from the same samples.  The set-up
is therefore cached here under a key made of the profile's content (the bytes of its samples and
every number the set-up depends on), never its identity, so that equal tables share it and
different ones never do.

Dask runs chunks on threads: ``get`` builds a missing entry once while other threads asking for
the same key wait for it (different keys build in parallel), and the cache holds at most
``max_entries`` entries and ``max_bytes`` bytes of arrays, dropping the least recently used.
"""
from __future__ import annotations

import threading
from collections import OrderedDict
from typing import Any, Callable, Hashable

import numpy as np

__all__ = ["SetupCache", "SETUP", "nbytes", "content_key"]


def nbytes(value: Any, _depth: int = 0) -> int:
    """Bytes held in NumPy arrays by ``value`` (tuples, lists, dicts and plain objects walked)."""
    if isinstance(value, np.ndarray):
        return int(value.nbytes)
    if _depth > 4:
        return 0
    if isinstance(value, (tuple, list)):
        return sum(nbytes(v, _depth + 1) for v in value)
    if isinstance(value, dict):
        return sum(nbytes(v, _depth + 1) for v in value.values())
    if hasattr(value, "__dict__"):
        return nbytes(vars(value), _depth + 1)
    return 0


def content_key(*arrays) -> tuple:
    """The exact content of the arrays as float64 bytes with their lengths (no hash collisions:
    the cache compares keys by equality)."""
    out = []
    for a in arrays:
        a = np.ascontiguousarray(np.asarray(a, dtype=float).ravel())
        out += [a.size, a.tobytes()]
    return tuple(out)


class SetupCache:
    """Least-recently-used cache of built values; ``get(key, build)`` returns the value of ``key``,
    calling ``build()`` once if it is missing.  ``hits`` and ``builds`` count the lookups."""

    def __init__(self, max_entries: int, max_bytes: int):
        self.max_entries = int(max_entries)
        self.max_bytes = int(max_bytes)
        self._lock = threading.Lock()
        self._items: OrderedDict[Hashable, tuple[Any, int]] = OrderedDict()
        self._building: dict[Hashable, threading.Event] = {}
        self._bytes = 0
        self.hits = 0
        self.builds = 0

    def get(self, key: Hashable, build: Callable[[], Any]) -> Any:
        while True:
            with self._lock:
                item = self._items.get(key)
                if item is not None:
                    self._items.move_to_end(key)
                    self.hits += 1
                    return item[0]
                done = self._building.get(key)
                owner = done is None
                if owner:
                    done = self._building[key] = threading.Event()
            if owner:
                break
            done.wait()     # another thread builds it; then look again (it may have failed)
        try:
            value = build()
            size = nbytes(value)
        except BaseException:
            with self._lock:
                del self._building[key]
            done.set()
            raise
        with self._lock:
            # stored and released under one lock: a waiter woken by ``done`` finds the value
            del self._building[key]
            self.builds += 1
            if size <= self.max_bytes:
                self._items[key] = (value, size)
                self._bytes += size
                while len(self._items) > self.max_entries or self._bytes > self.max_bytes:
                    _, (_, dropped) = self._items.popitem(last=False)
                    self._bytes -= dropped
        done.set()
        return value

    def clear(self) -> None:
        with self._lock:
            self._items.clear()
            self._bytes = 0

    def __len__(self) -> int:
        return len(self._items)


#: the one cache of the profile set-ups: 64 entries (a sweep over a few profiles and their
#: tolerance rows) and 512 MB (the axisymmetric block tree of a 1e4-sample table at rtol 1e-14 holds
#: ~27 MB, its g' table ~4 MB)
SETUP = SetupCache(max_entries=64, max_bytes=512 << 20)
