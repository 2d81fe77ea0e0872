"""A cache whose results are returned as copies.

The expensive results that analyses share (flights, tables) are computed once; callers get
their own copy, so a notebook that edits a table it was given corrupts nothing for the next
caller (the ledger, another figure)."""

from __future__ import annotations

import copy
from collections.abc import Callable
from functools import cache, wraps
from typing import ParamSpec, TypeVar

__all__ = ["cached_copies"]

P = ParamSpec("P")
R = TypeVar("R")


def cached_copies(function: Callable[P, R]) -> Callable[P, R]:
    """``functools.cache`` of ``function``, returning a deep copy of the cached result."""
    cached: Callable[..., R] = cache(function)

    @wraps(function)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        return copy.deepcopy(cached(*args, **kwargs))

    wrapper.cache_clear = cached.cache_clear  # type: ignore[attr-defined]
    return wrapper
