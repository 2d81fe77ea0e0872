"""Compiled kernels: numba's ``njit`` with an on-disk cache, and the helpers that let one source
serve numpy and compiled code.

The engines' inner loops (the 3DOF's right-hand side and integrator, the MKS's per-launch
constants) run as machine code compiled by numba. Compilation happens once per user, per version
of the package and per compiler: :func:`jit` keeps the machine code on disk
(:mod:`.numba_cache`) in a folder named by a digest of what alone decides it
(:func:`.kernel_digest.cache_folder`), so that every checkout of the same sources shares it.
(An error raised inside a kernel that was loaded names, in its traceback, the file of the
checkout that compiled it: the same source, line for line, elsewhere.)

Each engine with kernels has a ``warm_up()`` that compiles them ahead of use (or loads them);
``make`` calls it whenever the sources change, which keeps compilation out of the notebooks'
critical path.

The physics is written once. A formula meant for both worlds is decorated :func:`formula`: it
stays a plain Python function that numpy runs on arrays, and compiled code inlines the same
source for numbers. It uses numpy's functions, which numba also compiles for numbers, and
:func:`select` for a choice between two values (``np.where`` on arrays; numba's own
``np.where`` would return a 0-d array for numbers, an allocation per call). ``bisect_right``
compiles too (as numpy's ``searchsorted``).
"""

from __future__ import annotations

from bisect import bisect_right
from collections.abc import Callable
from typing import Any, TypeVar

import numba
import numpy as np
from numba import types
from numba.extending import overload, register_jitable

from . import numba_cache

__all__ = ["jit", "formula", "select", "vector"]

F = TypeVar("F", bound=Callable[..., Any])


def jit(
    function: F | None = None,
    *,
    inline: bool = False,
    cache: bool = True,
    zero_division: str = "raise",
) -> Any:
    """``function`` compiled in nopython mode and cached on disk (:mod:`.numba_cache`), without
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
    return numba_cache.cache_on_disk(dispatcher)


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
