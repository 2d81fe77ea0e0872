"""Compiled kernels: numba's ``njit`` with an on-disk cache, and the helpers that let one source
serve numpy and compiled code.

The engines' inner loops (the 3DOF's right-hand side and integrator, the MKS's per-launch
constants) run as machine code compiled by numba. Compilation happens once per version of the
package: the machine code is cached on disk in a folder named by a digest of the sources the
kernel's module reaches (numba itself would only notice a change in the file of the compiled
function, not in a formula it calls from another module). Each engine with kernels has a
``warm_up()`` that compiles them ahead of use; ``make`` calls it whenever the sources change,
which keeps compilation out of the notebooks' critical path.

The physics is written once. A formula meant for both worlds is decorated :func:`formula`: it
stays a plain Python function that numpy runs on arrays, and compiled code inlines the same
source for numbers. It uses numpy's functions, which numba also compiles for numbers, and
:func:`select` for a choice between two values (``np.where`` on arrays; numba's own
``np.where`` would return a 0-d array for numbers, an allocation per call). ``bisect_right``
compiles too (as numpy's ``searchsorted``).
"""

from __future__ import annotations

import hashlib
import os
import sys
from bisect import bisect_right
from collections.abc import Callable
from functools import cache
from pathlib import Path
from types import ModuleType
from typing import Any, TypeVar

import numba
import numpy as np
from numba import types
from numba.extending import overload, register_jitable

__all__ = ["jit", "formula", "select", "vector", "cache_folder"]

F = TypeVar("F", bound=Callable[..., Any])


def _sources(module_name: str) -> list[Path]:
    """The package's source files that ``module_name`` reaches through what it has imported."""
    seen, pending = set(), [module_name]
    while pending:
        name = pending.pop()
        if name in seen:
            continue
        seen.add(name)
        for value in vars(sys.modules[name]).values():
            owner = (
                value.__name__
                if isinstance(value, ModuleType)
                else getattr(value, "__module__", "")
            )
            if (
                isinstance(owner, str)
                and owner.startswith(f"{__package__}.")
                and owner in sys.modules
            ):
                pending.append(owner)
    return sorted(Path(str(sys.modules[name].__file__)) for name in seen)


@cache
def cache_folder(module_name: str) -> Path:
    """Where the compiled kernels of ``module_name`` are kept: under ``NUMBA_CACHE_DIR`` if set,
    else the user's cache folder, in a folder named by a digest of every source file of the
    package that the module reaches (an edit to any of them compiles afresh)."""
    digest = hashlib.sha256()
    for source in _sources(module_name):
        digest.update(source.name.encode() + source.read_bytes())
    root = os.environ.get("NUMBA_CACHE_DIR") or Path(
        os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    )
    return Path(root) / "harp-analysis" / digest.hexdigest()[:16]


def jit(function: F | None = None, *, inline: bool = False) -> Any:
    """``function`` compiled in nopython mode and cached in :func:`cache_folder`, without
    fast-math (IEEE results, as numpy's where the operations are the same). ``inline=True``
    (as ``@jit(inline=True)``) inlines it into compiled callers: a call that passes arrays
    otherwise costs reference counting, tens of nanoseconds in a right-hand side."""
    if function is None:
        return lambda function: jit(function, inline=inline)
    config: Any = numba.config
    previous = config.CACHE_DIR
    config.CACHE_DIR = str(cache_folder(function.__module__))  # read where caching starts
    try:
        return numba.njit(cache=True, inline="always" if inline else "never")(function)
    finally:
        config.CACHE_DIR = previous


def formula(function: F) -> F:
    """``function`` unchanged for Python and numpy, and callable from compiled code."""
    return register_jitable(function)


@formula
def vector(x, y, z):
    """A 3-vector written per component in compiled code: ``vector(ax - bx, ay - by, az - bz)``
    is numpy's ``a - b``; the operation counts of :mod:`harp_analysis.effort` count it once,
    as they count numpy's (3, n) expression (its costliest component)."""
    return x, y, z


def select(condition, if_true, if_false):
    """``if_true`` where ``condition`` holds, else ``if_false``: ``np.where`` (both evaluated,
    as numpy does); on a plain bool, and in compiled code on numbers, one of the two."""
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
