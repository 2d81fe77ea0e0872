"""Sweeps: the one way a function runs over many independent items (maps, Monte Carlo).

:func:`sweep` calls ``function(item)`` for every item and returns the results in the items'
order: in this process by default, with a progress bar (tqdm) when someone is watching, or on
a Dask cluster when given its ``client`` (any object with Dask's ``map`` and ``gather``; Dask
itself is not imported here). ``function`` and the items must then be picklable: a module-level
function, or a :func:`functools.partial` of one, not a lambda or a closure.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterable
from typing import Any, TypeVar

__all__ = ["sweep", "interactive"]

Item = TypeVar("Item")
Result = TypeVar("Result")


def interactive() -> bool:
    """Whether a person is likely watching: standard error is a terminal, or the kernel was
    started by a Jupyter server (which sets ``JPY_SESSION_NAME``; nbclient and nbmake, which
    run notebooks headless, do not)."""
    stream = sys.stderr
    terminal = stream is not None and hasattr(stream, "isatty") and stream.isatty()
    return bool(terminal) or "JPY_SESSION_NAME" in os.environ


def _check_client(client) -> None:
    missing = [name for name in ("map", "gather") if not callable(getattr(client, name, None))]
    if missing:
        raise TypeError(
            f"client must be a Dask client (with map and gather); {type(client).__name__} "
            f"has no {' or '.join(missing)}"
        )


def sweep(
    function: Callable[[Item], Result],
    items: Iterable[Item],
    *,
    client: Any = None,
    progress: bool = True,
    description: str | None = None,
) -> list[Result]:
    """``[function(item) for item in items]``, in the items' order.

    In this process, with a tqdm bar labelled ``description`` if ``progress`` and the session
    is :func:`interactive`; on a Dask cluster if ``client`` is given (``client.map`` then
    ``client.gather``; the cluster shows its own progress in its dashboard)."""
    if not callable(function):
        raise TypeError(f"function must be callable; got {type(function).__name__}")
    items = list(items)
    if client is not None:
        _check_client(client)
        return list(client.gather(client.map(function, items)))
    if progress and interactive() and items:
        try:
            from tqdm import tqdm
        except ImportError:  # tqdm is pinned in environment.txt; a bare install may lack it
            pass
        else:
            return [function(item) for item in tqdm(items, desc=description, leave=False)]
    return [function(item) for item in items]
