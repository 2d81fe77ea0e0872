"""Two hooks into numba's dispatcher that keep compiled kernels on disk once per user, safely
under concurrent use; ``HARP_ANALYSIS_NUMBA_CACHE=0`` turns both off.

The cache. ``numba.njit(cache=True)`` keeps a kernel's machine code in a folder named by its
source file's location, stamped by that one file's modification time: each checkout compiles
afresh, and a change to a formula the kernel imports from another module is not noticed, so a
stale kernel runs (numba issue 1833, open; issue 9350 asks for control of the location). The
hook: the dispatcher's private ``_cache`` (a ``NullCache`` until ``enable_caching``) is replaced
by numba's own ``FunctionCache`` with a locator of ours (``numba.core.caching._CacheLocator``),
which puts the files in :func:`.kernel_digest.cache_folder`, named by the contents of every
source the kernel reaches and by the toolchain.

The lock. Processes that compile one kernel at once (two notebooks opened after an upgrade,
two checkouts' ``make``) each compile it and each read, extend and rewrite numba's index of its
cache files, which may lose the other's entries (numba issues 4807 and 10128, open; numba's
maintainers suggested a file lock in 10128). The hook: the dispatcher's ``compile`` method,
through which numba loads or compiles a signature, is wrapped to take turns under a file lock per
kernel, the later process loading what the first saved.

The switch: ``HARP_ANALYSIS_NUMBA_CACHE=0`` leaves numba's dispatcher as ``numba.njit`` makes it,
with no disk cache at all (numba's own, keyed by location, would risk the stale kernels above):
the same machine code and the same results, compiled afresh by every process (about a minute
of CPU for the engines, instead of seconds to load them). Under a numba whose dispatcher is not
shaped as the hooks expect, they stay off with a warning naming this module.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numba
from filelock import FileLock
from numba.core.caching import (
    CompileResultCacheImpl,
    FunctionCache,
    NullCache,
    _CacheLocator,
)
from numba.core.compiler_lock import global_compiler_lock

from .kernel_digest import cache_folder

__all__ = ["SWITCH", "enabled", "cache_on_disk"]

#: The environment variable that turns the hooks off when "0".
SWITCH = "HARP_ANALYSIS_NUMBA_CACHE"


def enabled() -> bool:
    """Whether the hooks are on (:data:`SWITCH` is not "0")."""
    return os.environ.get(SWITCH, "1") != "0"


def cache_on_disk(dispatcher: Any) -> Any:
    """``dispatcher`` (``numba.njit``'s, not yet compiled) with its machine code kept in
    :func:`.kernel_digest.cache_folder` of its function's module and compiled under a file lock
    there: what ``njit(cache=True)`` does (``Dispatcher.enable_caching``), with the cache found
    by content. Unchanged where the hooks are off."""
    if not enabled():
        return dispatcher
    if not isinstance(getattr(dispatcher, "_cache", None), NullCache):
        warnings.warn(
            f"numba {numba.__version__}'s dispatcher keeps no _cache to replace: kernels are "
            f"compiled in every process (harp_analysis.foundation.numba_cache)",
            RuntimeWarning,
            stacklevel=3,
        )
        return dispatcher
    function = dispatcher.py_func
    dispatcher._cache = _KernelCache(function)
    folder = Path(dispatcher._cache.cache_path)
    lock = folder / f"{function.__qualname__}-{function.__code__.co_firstlineno}.lock"
    dispatcher.compile = _under_lock(dispatcher.compile, lock)
    return dispatcher


class _ContentLocator(_CacheLocator):
    """Tells numba where a kernel's cache files are (:func:`.kernel_digest.cache_folder` of its
    module) and what stamps their sources (the folder's digest), not numba's default: a folder
    named by the source file's location and a stamp of that one file, which put each checkout's
    kernels apart. numba's index within the folder is named by the module's file name, the
    function's name and its first line (and the Python version), and keys each entry by the
    signature, the target and the function's bytecode: none of them depends on a path or a
    time."""

    def __init__(self, py_func: Callable, py_file: str) -> None:
        self._py_file = py_file  # numba's warnings name it
        self._lineno = py_func.__code__.co_firstlineno
        self._folder = cache_folder(py_func.__module__)

    @classmethod
    def from_function(cls, py_func: Callable, py_file: str) -> _ContentLocator:
        return cls(py_func, py_file)

    def get_cache_path(self) -> str:
        return str(self._folder)

    def get_source_stamp(self) -> str:
        return self._folder.name

    def get_disambiguator(self) -> str:
        return str(self._lineno)


class _KernelCacheImpl(CompileResultCacheImpl):
    _locator_classes = [_ContentLocator]


class _KernelCache(FunctionCache):
    """numba's cache of a dispatcher's compiled signatures, kept where :class:`_ContentLocator`
    says."""

    _impl_class = _KernelCacheImpl


def _under_lock(compile: Callable, path: Path) -> Callable:
    """``compile`` (a dispatcher's: load from the disk cache, else compile and save) run under
    the file lock ``path``, so another process waits and then loads what this one saved. One
    lock per kernel, taken caller before callee, cannot deadlock (calls form no cycle, and a
    recursive kernel re-enters its own lock); numba's own lock is taken first, as it is in
    ``compile``, so that threads take the two in one order."""
    lock = FileLock(path)

    def compile_under_lock(signature):
        with global_compiler_lock:
            path.parent.mkdir(parents=True, exist_ok=True)
            with lock:
                return compile(signature)

    return compile_under_lock
