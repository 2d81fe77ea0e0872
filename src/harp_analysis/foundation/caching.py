"""The package's one cache of shared results: each caller gets its own deep copy.

The expensive results that analyses share (flights, tables, fitted arrays) are computed once;
callers get their own copy, so a notebook that edits a table or an array it was given corrupts
nothing for the next caller (the ledger, another figure, the next Monte Carlo). Copies were
chosen over read-only views because the results are DataFrames as often as arrays (pandas has
no read-only frame) and a deep copy of the largest shared result costs well under a
millisecond next to the seconds it caches. A plain ``functools.cache`` is left only on functions
whose results cannot be edited (numbers, strings, tuples of them, frozen dataclasses of them):
``tests/test_caching.py`` holds that list and fails on any other."""

from __future__ import annotations

import copy
import inspect
from collections.abc import Callable
from functools import cache, wraps
from typing import ParamSpec, TypeVar

__all__ = ["cached_copies"]

P = ParamSpec("P")
R = TypeVar("R")


def _unhashable_argument(function: Callable, args: tuple, kwargs: dict) -> str | None:
    """The name of the first argument of ``function`` whose value cannot be hashed, if any."""
    try:
        bound = inspect.signature(function).bind(*args, **kwargs)
    except TypeError:
        return None
    for name, value in bound.arguments.items():
        try:
            hash(value)
        except TypeError:
            return name
    return None


def cached_copies(function: Callable[P, R]) -> Callable[P, R]:
    """``functools.cache`` of ``function``, returning a deep copy of the cached result. An
    argument that cannot be a cache key (a list, a dict) raises ``TypeError`` naming it."""
    cached: Callable[..., R] = cache(function)

    @wraps(function)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        try:
            result = cached(*args, **kwargs)
        except TypeError:  # the cache hashes the arguments before calling
            name = _unhashable_argument(function, args, kwargs)
            if name is None:
                raise
            raise TypeError(
                f"{function.__name__}: {name} must be hashable (a tuple, not a list or dict)"
            ) from None
        return copy.deepcopy(result)

    wrapper.cache_clear = cached.cache_clear  # type: ignore[attr-defined]
    return wrapper
