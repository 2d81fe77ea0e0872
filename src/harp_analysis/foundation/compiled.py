"""Compiled kernels: numba's ``njit`` with an on-disk cache, and the helpers that let one source
serve numpy and compiled code.

The engines' inner loops (the 3DOF's right-hand side and integrator, the MKS's per-launch
constants) run as machine code compiled by numba. Compilation happens once per user, per version
of the package and per compiler: the machine code is cached on disk in a folder named by a digest
of what alone decides it (:func:`cache_folder`): the contents of every source file of the package
the kernel's module reaches (numba itself would only notice a change in the file of the compiled
function, not in a formula it calls from another module), and the versions that compile it
(numba's, llvmlite's, Python's, and the CPU's name and features as numba sees them). Neither the
files' paths nor their modification times count: every checkout, worktree, virtual environment
and CI run of the same sources and versions on a machine shares the one folder, so a fresh clone
loads the kernels another compiled (numba's own cache, keyed by each file's location, would
compile them all again). The folders live in the user's cache folder,
``$XDG_CACHE_HOME/harp-analysis/kernels`` (``~/.cache/harp-analysis/kernels`` if
``XDG_CACHE_HOME`` is unset); ``HARP_ANALYSIS_KERNEL_CACHE`` names another folder to keep them in
(``NUMBA_CACHE_DIR``, if set and it is not, puts them in its ``harp-analysis/kernels``).
A folder no version uses any more is never read again, and may be deleted. (An error raised inside
a kernel that was loaded names, in its traceback, the file of the checkout that compiled it: the
same source, line for line, elsewhere.)

Each engine with kernels has a ``warm_up()`` that compiles them ahead of use (or loads them);
``make`` calls it whenever the sources change, which keeps compilation out of the notebooks'
critical path. Processes that compile the same kernel at once (two notebooks opened after an
upgrade, two checkouts' ``make``) take turns under a file lock per kernel in its folder, the later
one loading what the first saved: unguarded, each compiles, and each reads, extends and rewrites
numba's index of the kernel's cache files, which may lose the other's entries.

The physics is written once. A formula meant for both worlds is decorated :func:`formula`: it
stays a plain Python function that numpy runs on arrays, and compiled code inlines the same
source for numbers. It uses numpy's functions, which numba also compiles for numbers, and
:func:`select` for a choice between two values (``np.where`` on arrays; numba's own
``np.where`` would return a 0-d array for numbers, an allocation per call). ``bisect_right``
compiles too (as numpy's ``searchsorted``).
"""

from __future__ import annotations

import ast
import hashlib
import os
import sys
from bisect import bisect_right
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any, TypeVar

import llvmlite
import numba
import numpy as np
from filelock import FileLock
from numba import types
from numba.core.caching import (
    CompileResultCacheImpl,
    FunctionCache,
    NullCache,
    _CacheLocator,
)
from numba.core.compiler_lock import global_compiler_lock
from numba.extending import overload, register_jitable

__all__ = ["jit", "formula", "select", "vector", "cache_folder", "cache_root"]

F = TypeVar("F", bound=Callable[..., Any])


_PACKAGE = Path(__file__).parents[1]  # the package's root folder
_PACKAGE_NAME = __name__.partition(".")[0]


def _imported(source: Path) -> frozenset[Path]:
    """The package's source files that ``source`` imports (``from . import x``, ``from .x
    import y``, ``import harp_analysis.x``), constants included: numba bakes them in."""
    return _imported_as_of(source, *_stamp(source))


def _stamp(source: Path) -> tuple[int, int]:
    status = source.stat()
    return status.st_mtime_ns, status.st_size


@cache
def _imported_as_of(source: Path, mtime_ns: int, size: int) -> frozenset[Path]:
    """:func:`_imported` of ``source`` as it was at that modification time and size (a file
    is parsed once per version, not once per compiled function). A relative import is resolved
    against the folder of ``source`` itself (``from ..models import drag`` in a subpackage), an
    absolute one against the package's root: either way every module a kernel reaches counts."""
    found: set[Path] = set()
    for node in ast.walk(ast.parse(source.read_text())):
        if isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if node.level:
                base = source.parent
                for _ in range(node.level - 1):
                    base = base.parent
            elif module == _PACKAGE_NAME or module.startswith(f"{_PACKAGE_NAME}."):
                base, module = _PACKAGE, module.removeprefix(_PACKAGE_NAME).lstrip(".")
            else:  # another package's
                continue
            found.update(_module_files(base, module, [alias.name for alias in node.names]))
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith(f"{_PACKAGE_NAME}."):
                    found.update(_module_files(_PACKAGE, alias.name.partition(".")[2], []))
    return frozenset(found)


def _module_files(base: Path, module: str, names: list[str]) -> list[Path]:
    """The source files of ``module`` (dotted, below ``base``; empty: ``base`` itself) and of
    those of ``names`` that are its submodules: a module's file or a subpackage's
    ``__init__.py``."""
    folder = base.joinpath(*module.split(".")) if module else base
    candidates = [folder.with_suffix(".py"), folder / "__init__.py"] if module else []
    for name in names:
        candidates += [folder / f"{name}.py", folder / name / "__init__.py"]
    return [path for path in candidates if path.is_file()]


def _sources(module_name: str) -> list[Path]:
    """The package's source files that ``module_name`` reaches, import by import."""
    seen: set[Path] = set()
    pending = [Path(str(sys.modules[module_name].__file__))]
    while pending:
        source = pending.pop()
        if source not in seen:
            seen.add(source)
            pending.extend(_imported(source))
    return sorted(seen)


def cache_root() -> Path:
    """The folder that holds the kernels' folders: ``HARP_ANALYSIS_KERNEL_CACHE`` if set, else
    ``harp-analysis/kernels`` in ``NUMBA_CACHE_DIR`` if that is set, else in the user's cache
    folder (``XDG_CACHE_HOME``, by default ``~/.cache``)."""
    if chosen := os.environ.get("HARP_ANALYSIS_KERNEL_CACHE"):
        return Path(chosen)
    root = os.environ.get("NUMBA_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME")
    return Path(root or Path.home() / ".cache") / "harp-analysis" / "kernels"


def cache_folder(module_name: str) -> Path:
    """Where the compiled kernels of ``module_name`` are kept: in :func:`cache_root`, in a
    folder named by a digest of the module's name, of the contents of every source file of the
    package that the module reaches, as they are now (an edit to any of them, or a reload after
    one, compiles afresh), and of :func:`_toolchain` (another numba, llvmlite, Python or CPU
    compiles afresh). Where the files are, and when they were written, does not count."""
    sources = tuple(_sources(module_name))
    stamps = tuple(_stamp(source) for source in sources)
    return cache_root() / _digest(module_name, sources, stamps, _toolchain())


@cache
def _toolchain() -> str:
    """What compiles the kernels, as numba sees it: numba's, llvmlite's and Python's versions,
    and the target (numba's "magic tuple": the triple, the CPU's name and its features, with
    ``NUMBA_CPU_NAME`` and ``NUMBA_CPU_FEATURES`` applied), which numba also keys its index by."""
    from numba.core.registry import cpu_target

    python = f"{sys.implementation.cache_tag}{sys.abiflags} {sys.version}"
    target = cpu_target.target_context.codegen().magic_tuple()
    return repr((numba.__version__, llvmlite.__version__, python, target))


@cache
def _digest(module_name: str, sources: tuple[Path, ...], stamps: tuple, toolchain: str) -> str:
    """The digest of ``module_name``, of ``sources`` at these modification times and sizes
    (read once each; each named by its path in the package, the times not hashed) and of
    ``toolchain``."""
    digest = hashlib.sha256(f"{module_name}\n{toolchain}\n".encode())
    for name, source in sorted((_name_in_package(source), source) for source in sources):
        content = source.read_bytes()
        digest.update(f"{name}\n{len(content)}\n".encode() + content)
    return digest.hexdigest()[:16]


def _name_in_package(source: Path) -> str:
    """``source``'s path within the package (``engines/mks.py``), or its name if outside it (a
    module of the caller's that compiles kernels with :func:`jit`)."""
    return (
        source.relative_to(_PACKAGE).as_posix() if source.is_relative_to(_PACKAGE) else source.name
    )


class _ContentLocator(_CacheLocator):
    """Tells numba where a kernel's cache files are (:func:`cache_folder` of its module) and
    what stamps their sources (the folder's digest), not numba's default: a folder named by
    the source file's location and a stamp of that one file, which put each checkout's kernels
    apart. numba's index within the folder is named by the module's file name, the function's
    name and its first line (and the Python version), and keys each entry by the signature,
    the target and the function's bytecode: none of them depends on a path or a time."""

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


def jit(
    function: F | None = None,
    *,
    inline: bool = False,
    cache: bool = True,
    zero_division: str = "raise",
) -> Any:
    """``function`` compiled in nopython mode and cached in :func:`cache_folder`, without
    fast-math (IEEE results, as numpy's where the operations are the same).

    ``inline=True`` (as ``@jit(inline=True)``) inlines it into compiled callers in numba's own
    representation, before typing: a call that passes arrays otherwise costs reference counting,
    tens of nanoseconds in a right-hand side. Each call site copies the callee's code whole and
    types it again (most of a kernel's compilation, measured), so inline only what runs at every
    step; LLVM inlines small callees of the others by itself.

    ``cache=False`` keeps the machine code in memory only, for a function compiled only as a
    part of cached kernels (whose files hold it): one cache per kernel, not one shared by them,
    lets processes compile different kernels at once (each cached function is compiled under
    its own file lock).

    ``zero_division="ieee"`` lets ``/`` by zero give inf or NaN as numpy's does, where Python's
    rule (``"raise"``, the default) raises ZeroDivisionError: a test and a branch at every
    division (numba's ``error_model``), for a kernel that checks its results for them itself."""
    if zero_division not in ("raise", "ieee"):
        raise ValueError(f"zero_division must be 'raise' or 'ieee'; got {zero_division!r}")
    if function is None:
        return lambda function: jit(
            function, inline=inline, cache=cache, zero_division=zero_division
        )
    dispatcher: Any = numba.njit(
        inline="always" if inline else "never",
        error_model="numpy" if zero_division == "ieee" else "python",
    )(function)
    config: Any = numba.config
    if config.DISABLE_JIT or not cache:  # NUMBA_DISABLE_JIT=1 (debugging) returned the function
        return dispatcher
    # what njit(cache=True) does (Dispatcher.enable_caching), with the cache found by content
    if not isinstance(getattr(dispatcher, "_cache", None), NullCache):
        raise RuntimeError(f"numba {numba.__version__}'s dispatcher keeps no _cache to replace")
    dispatcher._cache = _KernelCache(function)
    folder = Path(dispatcher._cache.cache_path)
    # numba compiles through this method at a first call, for a compiled caller and at warm-up
    lock = folder / f"{function.__qualname__}-{function.__code__.co_firstlineno}.lock"
    dispatcher.compile = _under_lock(dispatcher.compile, lock)
    return dispatcher


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


def formula(function: F) -> F:
    """``function`` unchanged for Python and numpy, and callable from compiled code."""
    return register_jitable(function)


@formula
def vector(x, y, z):
    """A 3-vector written per component in compiled code: ``vector(ax - bx, ay - by, az - bz)``
    is numpy's ``a - b``; the operation counts of :mod:`harp_analysis.analyses.effort` count it
    once, as they count numpy's (3, n) expression (its costliest component)."""
    return x, y, z


def select(condition, if_true, if_false):
    """``if_true`` where ``condition`` holds, else ``if_false``: ``np.where`` on arrays, the
    chosen one of two numbers on a plain bool and in compiled code (both are evaluated before
    the call in every case: the formulas count both, as numpy computes both)."""
    if isinstance(condition, bool):
        return if_true if condition else if_false
    return np.where(condition, if_true, if_false)


@overload(bisect_right)
def _bisect_right_compiled(table, value):
    # numba has no bisect module; its searchsorted is the same search
    return lambda table, value: np.searchsorted(table, value, side="right")


@overload(select)
def _select_compiled(condition, if_true, if_false):
    if isinstance(condition, types.Boolean):
        return lambda condition, if_true, if_false: if_true if condition else if_false
    return lambda condition, if_true, if_false: np.where(condition, if_true, if_false)
