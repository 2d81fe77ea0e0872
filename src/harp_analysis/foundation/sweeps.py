"""Sweeps: the one way a function runs over many independent items (maps, Monte Carlo).

:func:`sweep` calls ``function(item)`` for every item and returns the results in the items'
order, or folds them in that order into one state (``reduce``), so that a Monte Carlo of a
million samples keeps no more than a window of items and results in memory. It runs in this
process by default, with a progress bar (tqdm) when someone is watching, or on a Dask cluster
when given its ``client`` (``distributed`` is imported only then). Either way the results are
the same, bit for bit: each is folded in the items' order, whichever worker ran it and whenever
it finished. A worker lost mid-sweep costs a rerun of its tasks (the scheduler's
``allowed-failures``), never a lost or a duplicated result. On a cluster, ``function`` and the
items travel by cloudpickle: a module's function by its name (the workers must import it), a
lambda, closure or :func:`functools.partial` by value.

:func:`chunks` splits a sample count into ranges of indices (:func:`client_shares` a list of
items among a cluster's threads), and :func:`sample_chunk` draws one range's points of a seeded
sample (Sobol' or Philox), so that a chunk's samples depend only on the seed and its indices:
the chunks, concatenated, are the single draw.
"""

from __future__ import annotations

import os
import sys
import warnings
from collections.abc import Callable, Generator, Iterable, Sized
from contextlib import closing, contextmanager
from typing import Any, TypeVar

import numpy as np
from scipy.stats import qmc

from .validation import check_choice, whole_number

__all__ = [
    "sweep",
    "SweepLengthError",
    "MAX_ITEMS",
    "MAX_CHUNK_NUMBERS",
    "interactive",
    "chunks",
    "client_shares",
    "sample_chunk",
    "SAMPLING_METHODS",
]

Item = TypeVar("Item")
Result = TypeVar("Result")

SAMPLING_METHODS = ("sobol", "random")

#: Items a sweep takes by default at most: an endless iterator stops with
#: :class:`SweepLengthError` instead of running until the machine's memory or patience ends.
MAX_ITEMS = 10**6


#: Numbers one chunk of a sample holds at most (800 MB of floats).
MAX_CHUNK_NUMBERS = 10**8


class SweepLengthError(ValueError):
    """A sweep was given more items than its ``max_items`` (an endless iterator, or a typo)."""


def interactive() -> bool:
    """Whether a person is likely watching: standard error is a terminal, or the kernel was
    started by a Jupyter server (which sets ``JPY_SESSION_NAME``; nbclient and nbmake, which
    run notebooks headless, do not)."""
    stream = sys.stderr
    terminal = stream is not None and hasattr(stream, "isatty") and stream.isatty()
    return bool(terminal) or "JPY_SESSION_NAME" in os.environ


def _check_client(client) -> None:
    if not callable(getattr(client, "submit", None)):
        raise TypeError(
            f"client must be a Dask client (a distributed.Client, with submit); "
            f"{type(client).__name__} has no submit"
        )


def _default_window(client) -> int:
    """Twice the cluster's threads, so that every thread has a task queued behind its current
    one; 4 if the client cannot tell."""
    nthreads = getattr(client, "nthreads", None)
    threads = sum(nthreads().values()) if callable(nthreads) else 0
    return 2 * threads if threads else 4


@contextmanager
def _progress_bar(progress: bool, total: int | None, description: str | None):
    """Yields the function that counts one item done: a tqdm bar's when someone watches."""
    if progress and interactive():
        try:
            from tqdm import tqdm
        except ImportError:  # tqdm is pinned in environment.txt; a bare install may lack it
            pass
        else:
            with tqdm(total=total, desc=description, leave=False) as bar:
                yield bar.update
            return
    yield lambda: None


_RAISED_BY = "raised by item {} of the sweep"  # the note on a function's exception


def _bounded(items: Iterable, max_items: int) -> Generator:
    """``items``, raising :class:`SweepLengthError` when one more than ``max_items`` comes."""
    for index, item in enumerate(items):
        if index == max_items:
            raise SweepLengthError(
                f"items gave more than max_items={max_items} items (an endless iterator?); "
                f"pass a larger max_items to sweep more"
            )
        yield item


def _in_process(function, items: Iterable, advance: Callable[[], Any]) -> Generator:
    for index, item in enumerate(items):
        try:
            result = function(item)
        except Exception as error:
            error.add_note(_RAISED_BY.format(index))
            raise
        advance()
        yield result


def _on_cluster(function, items: Iterable, client, window: int, advance) -> Generator:
    """The results in the items' order, with at most ``window`` items submitted and not yet
    handed on. Each future is collected once, by its key, so a task the scheduler reran after
    losing a worker is not counted twice (and Dask's own rerun needs no ``retries``, which
    would only rerun a function's real exceptions)."""
    from distributed import as_completed

    source = enumerate(items)
    running: dict[str, tuple[int, Any]] = {}  # a future's key: the item's index, the future
    finished: dict[int, Any] = {}  # results waiting for an earlier item's
    completed = as_completed()
    next_index = 0

    def top_up():
        while len(running) + len(finished) < window:
            entry = next(source, None)
            if entry is None:
                return
            index, item = entry
            future = client.submit(function, item, pure=False)  # equal items: distinct tasks
            running[future.key] = (index, future)
            completed.add(future)

    try:
        top_up()
        for future in completed:
            if future.key not in running:
                continue
            index, _ = running.pop(future.key)
            try:
                finished[index] = future.result()
            except Exception as error:
                error.add_note(_RAISED_BY.format(index))
                raise
            advance()
            while next_index in finished:
                yield finished.pop(next_index)
                next_index += 1
            top_up()
    finally:
        if running:
            client.cancel([future for _, future in running.values()])


def sweep(
    function: Callable[[Item], Result],
    items: Iterable[Item],
    *,
    client: Any = None,
    progress: bool = True,
    description: str | None = None,
    reduce: Callable[[Any, Result], Any] | None = None,
    initial: Any = None,
    window: int | None = None,
    max_items: int = MAX_ITEMS,
) -> Any:
    """``[function(item) for item in items]``, in the items' order; or, given ``reduce``, the
    fold ``state = reduce(state, result)`` over those results in the items' order, starting from
    ``initial``, keeping nothing but the state and the items in flight.

    ``items`` may be any iterable, a lazy generator included: it is read as the sweep goes. In
    this process the items run one at a time; on a Dask cluster (``client``) at most ``window``
    of them are submitted and not yet folded (by default twice the cluster's threads). A tqdm
    bar labelled ``description`` counts the items done if ``progress`` and the session is
    :func:`interactive`; its total is known when ``items`` has a length. An exception raised by
    ``function`` comes out of the sweep with a note naming the item's index. More than
    ``max_items`` items raise :class:`SweepLengthError` (before any runs, if ``items`` has a
    length; when the one too many comes, if not)."""
    _check_callables(function, items, reduce, initial)
    total = len(items) if isinstance(items, Sized) else None
    max_items = whole_number(max_items, "max_items", low=1)
    if total is not None and total > max_items:
        raise SweepLengthError(
            f"items has {total} items, more than max_items={max_items}; pass a larger "
            f"max_items to sweep them"
        )
    items = _bounded(items, max_items)
    if window is not None:
        window = whole_number(window, "window", low=1)
    if client is not None:
        _check_client(client)
    with _progress_bar(progress, total, description) as advance:
        if client is None:
            results = _in_process(function, items, advance)
        else:
            window = window or _default_window(client)
            results = _on_cluster(function, items, client, window, advance)
        with closing(results):  # cancels a cluster's remaining tasks if the fold fails
            return _collected(results, reduce, initial)


def _check_callables(function, items, reduce, initial) -> None:
    """A TypeError unless :func:`sweep`'s ``function`` (and ``reduce``, if given) can be called,
    ``items`` iterated, and ``initial`` comes with a ``reduce``."""
    if not callable(function):
        raise TypeError(f"function must be callable; got {type(function).__name__}")
    if reduce is not None and not callable(reduce):
        raise TypeError(f"reduce must be callable; got {type(reduce).__name__}")
    if reduce is None and initial is not None:
        raise TypeError("initial is the start of reduce's fold; give it with reduce")
    if not isinstance(items, Iterable):
        raise TypeError(f"items must be iterable; got {type(items).__name__}")


def _collected(results: Iterable, reduce, initial) -> Any:
    """The ``results`` as a list, or folded by ``reduce`` from ``initial`` in their order."""
    if reduce is None:
        return list(results)
    state = initial
    for result in results:
        state = reduce(state, result)
    return state


def chunks(count: int, size: int) -> list[range]:
    """The half-open ranges of sample indices [0, size), [size, 2 size), ... that cover
    ``count`` samples, the last one shorter if ``size`` does not divide ``count``: the items of
    a sweep over a large sample (a list, so a progress bar knows its length)."""
    count = whole_number(count, "count", low=1)
    size = whole_number(size, "size", low=1)
    if -(-count // size) > MAX_ITEMS:
        raise SweepLengthError(
            f"count = {count} in chunks of size = {size} makes more than MAX_ITEMS = "
            f"{MAX_ITEMS} chunks; take larger chunks"
        )
    return [range(start, min(start + size, count)) for start in range(0, count, size)]


def client_shares(items: list[Item], client) -> list[list[Item]]:
    """``items`` in consecutive shares, four for each of ``client``'s threads (one at least):
    the items of a sweep on its cluster (:func:`sweep`) whose work is one vectorised call per
    share, few enough that each task is worth sending, enough that no thread waits long for
    the slowest."""
    _check_client(client)
    threads = max(1, sum(client.nthreads().values()))
    size = max(1, -(-len(items) // (4 * threads)))
    return [items[start : start + size] for start in range(0, len(items), size)]


def sample_chunk(seed: int, dimensions: int, indices: range, method: str = "sobol") -> np.ndarray:
    """Points ``indices`` (a range of sample numbers) of the sample of ``dimensions``-dimensional
    points in [0, 1)^dimensions drawn from ``seed``, shape (len(indices), dimensions). The points
    depend only on the seed and the indices, so chunks drawn by any worker in any order,
    concatenated, equal the one draw of their total count.

    ``method`` "sobol": scipy's scrambled Sobol' sequence (its balance holds for a whole sample
    of a power of 2 points; a chunk need not be one), fast-forwarded to the chunk's start;
    "random": numpy's Philox generator, its counter advanced to the chunk's start."""
    seed = whole_number(seed, "seed", low=0)
    dimensions = whole_number(dimensions, "dimensions", low=1)
    if not isinstance(indices, range) or indices.step != 1 or indices.start < 0:
        raise ValueError(f"indices must be a range of sample numbers >= 0, step 1; got {indices!r}")
    check_choice(method, "method", SAMPLING_METHODS)
    if len(indices) * dimensions > MAX_CHUNK_NUMBERS:
        raise ValueError(
            f"indices ({len(indices)} points) x dimensions ({dimensions}) exceed "
            f"MAX_CHUNK_NUMBERS = {MAX_CHUNK_NUMBERS} numbers in one chunk; draw smaller chunks"
        )
    if method == "sobol":
        if dimensions > qmc.Sobol.MAXDIM:
            raise ValueError(
                f"dimensions must be <= {qmc.Sobol.MAXDIM} for method 'sobol'; got {dimensions}"
            )
        engine = qmc.Sobol(dimensions, scramble=True, rng=seed)
        if indices.start:  # scipy's fast_forward cannot take 0 steps
            engine.fast_forward(indices.start)
        with warnings.catch_warnings():  # the balance is the whole sample's, not a chunk's
            warnings.filterwarnings("ignore", "The balance properties", UserWarning)
            return engine.random(len(indices))
    bit_generator = np.random.Philox(key=seed)
    # one 64-bit draw per number; Philox's counter steps over blocks of four draws
    blocks, within = divmod(indices.start * dimensions, 4)
    bit_generator.advance(blocks)
    bit_generator.random_raw(within)
    return np.random.Generator(bit_generator).random((len(indices), dimensions))
