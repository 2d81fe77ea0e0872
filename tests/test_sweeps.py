"""The one sweep: results in the items' order or folded in it, in process (bar or none) or on a
Dask cluster, bit for bit the same, with bounded memory and no sample lost or duplicated when a
worker dies; and the seeded sample whose chunks, concatenated, are the single draw."""

import dataclasses
import itertools
import logging
import math
import operator
import os
import signal
import time
import tracemalloc
from collections import Counter
from functools import partial

import numpy as np
import pytest
from distributed import Client, LocalCluster
from hypothesis import given
from hypothesis import strategies as st

from harp_analysis.foundation import sweeps
from harp_analysis.foundation.sweeps import chunks, sample_chunk, sweep

SEED = 20130501


def order_sensitive(state, result):
    """A fold whose value depends on the order of the results (a base-1000 numeral)."""
    return state * 1000 + result


def moments(seed, dimensions, indices):
    """A Monte Carlo chunk reduced at once: its count, and the sums of its points and squares."""
    points = sample_chunk(seed, dimensions, indices)
    return np.array([len(points), *points.sum(axis=0), *(points**2).sum(axis=0)])


def fail_on_three(item):
    if item == 3:
        raise ArithmeticError("three")
    return item


def fresh_random_number(item):
    return np.random.default_rng().random()


def slow_chunk(indices):
    time.sleep(0.2)
    return indices.start, sample_chunk(SEED, 2, indices, method="random")


class CountingItems:
    """An endless stream of items that counts how many were pulled from it."""

    def __init__(self):
        self.pulled = 0

    def __iter__(self):
        for item in itertools.count():
            self.pulled += 1
            yield item


class StopFolding(Exception):
    pass


def folds_until(limit, stream, window, state, result):
    """Folds ``limit`` results, checking that no more than ``window`` items were ever pulled
    ahead of the fold, then stops the endless sweep."""
    assert stream.pulled - state <= window
    if state + 1 == limit:
        raise StopFolding
    return state + 1


# In this process


def test_results_come_in_the_items_order():
    items = [5, 3, 9, 1, 7]
    assert sweep(partial(operator.mul, 2), items, progress=False) == [10, 6, 18, 2, 14]
    assert sweep(str, iter(range(4)), progress=False) == ["0", "1", "2", "3"]
    assert sweep(str, [], progress=False) == []


def test_the_fold_is_the_fold_of_the_list_in_the_items_order():
    items = [5, 3, 9, 1, 7]
    assert sweep(abs, items, reduce=order_sensitive, initial=0) == int("005003009001007")
    assert sweep(abs, [], reduce=order_sensitive, initial=0) == 0


def test_items_are_pulled_lazily_one_at_a_time():
    stream = CountingItems()
    with pytest.raises(StopFolding):
        sweep(abs, stream, reduce=partial(folds_until, 50, stream, 1), initial=0)
    assert stream.pulled == 50


def peak_bytes_and_totals(count, dimensions):
    """The peak memory of a folded Monte Carlo sweep over ``count`` samples, and its sums."""
    tracemalloc.start()
    totals = sweep(
        partial(moments, SEED, dimensions),
        chunks(count, 10_000),
        progress=False,
        reduce=operator.add,
        initial=np.zeros(1 + 2 * dimensions),
    )
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak, totals


def test_a_million_samples_in_bounded_memory():
    """The fold keeps three sums per dimension, never the samples: the peak is that of one
    chunk of 10,000 points, far below the 1e6 x 4 x 8 bytes the samples themselves take, and
    no higher than a tenth of the sweep's. The sums are checked against the uniform
    distribution's moments (1/2 and 1/3)."""
    dimensions = 4
    sample_chunk(SEED, dimensions, range(1))  # scipy's Sobol' table (3 MB) loads once
    peak, totals = peak_bytes_and_totals(1_000_000, dimensions)
    assert peak < 1_000_000 * dimensions * 8 / 10
    assert peak < 2 * peak_bytes_and_totals(100_000, dimensions)[0]
    assert totals[0] == 1_000_000
    # a scrambled Sobol' sample: errors near 1/n, far below Monte Carlo's 1/sqrt(n) = 1e-3
    np.testing.assert_allclose(totals[1 : 1 + dimensions] / 1e6, 1 / 2, atol=1e-5)
    np.testing.assert_allclose(totals[1 + dimensions :] / 1e6, 1 / 3, atol=1e-5)


def test_an_error_names_the_item_that_raised():
    with pytest.raises(ArithmeticError, match="three") as raised:
        sweep(fail_on_three, range(6), progress=False)
    assert raised.value.__notes__ == ["raised by item 3 of the sweep"]


def test_no_bar_when_progress_is_off_or_nobody_watches(monkeypatch, capsys):
    monkeypatch.setattr(sweeps, "interactive", lambda: True)
    assert sweep(abs, [-1, -2], progress=False, description="quiet") == [1, 2]
    assert "quiet" not in capsys.readouterr().err
    monkeypatch.setattr(sweeps, "interactive", lambda: False)
    assert sweep(abs, [-1, -2], description="headless") == [1, 2]
    assert "headless" not in capsys.readouterr().err


def test_the_bar_shows_when_someone_watches(monkeypatch, capsys):
    monkeypatch.setattr(sweeps, "interactive", lambda: True)
    assert sweep(abs, [-3, 4, -5], description="watched") == [3, 4, 5]
    bar = capsys.readouterr().err
    assert "watched" in bar and "/3" in bar  # a list's length is the bar's total
    assert sweep(abs, iter([-3, 4]), reduce=operator.add, initial=0, description="lazy") == 7
    bar = capsys.readouterr().err
    assert "lazy" in bar and "0it" in bar  # a generator's is unknown: items are counted


def test_interactive_follows_the_terminal_and_the_jupyter_server(monkeypatch):
    monkeypatch.delenv("JPY_SESSION_NAME", raising=False)
    assert sweeps.interactive() is False  # pytest captures standard error: not a terminal
    monkeypatch.setenv("JPY_SESSION_NAME", "notebook.ipynb")
    assert sweeps.interactive() is True


def test_bad_arguments_are_named():
    with pytest.raises(TypeError, match="function must be callable"):
        sweep(3, [1])
    with pytest.raises(TypeError, match="client must be a Dask client.*object has no submit"):
        sweep(abs, [1], client=object())
    with pytest.raises(TypeError, match="items must be iterable"):
        sweep(abs, 5)
    with pytest.raises(TypeError, match="reduce must be callable"):
        sweep(abs, [1], reduce=0, initial=0)
    with pytest.raises(TypeError, match="initial is the start of reduce's fold"):
        sweep(abs, [1], initial=0)
    with pytest.raises(ValueError, match=r"window must lie in \[1, inf\]; got 0"):
        sweep(abs, [1], window=0)
    with pytest.raises(ValueError, match="window must be a whole number; got 2.5"):
        sweep(abs, [1], window=2.5)


def test_an_endless_iterator_stops_at_max_items_by_name():
    stream = CountingItems()
    with pytest.raises(sweeps.SweepLengthError, match="more than max_items=50 .*endless"):
        sweep(abs, stream, max_items=50, progress=False)
    assert stream.pulled == 51  # the one too many, and nothing after it
    with pytest.raises(sweeps.SweepLengthError, match="max_items=1000000"):
        sweep(abs, itertools.count(), reduce=operator.add, initial=0, progress=False)
    assert sweep(abs, iter(range(50)), max_items=50, progress=False) == list(range(50))


def test_a_sized_sweep_beyond_max_items_is_refused_before_it_runs():
    calls = []
    with pytest.raises(sweeps.SweepLengthError, match="items has 11 items, more than max_items=10"):
        sweep(calls.append, range(11), max_items=10)
    assert calls == []
    with pytest.raises(TypeError, match="max_items must be a whole number"):
        sweep(abs, [1], max_items="10")


# Chunks and the seeded sample


def test_chunks_and_samples_beyond_memory_are_refused_by_name():
    with pytest.raises(sweeps.SweepLengthError, match="count = 1000000000000 in chunks of size"):
        chunks(10**12, 1)
    assert len(chunks(10**12, 10**6)) == 10**6
    with pytest.raises(ValueError, match=r"indices \(1000000000000 points\) x dimensions \(2\)"):
        sample_chunk(SEED, 2, range(10**12))
    with pytest.raises(ValueError, match="dimensions must be <= 21201 for method 'sobol'"):
        sample_chunk(SEED, 30_000, range(2))


@given(count=st.integers(1, 10_000), size=st.integers(1, 12_000))
def test_chunks_cover_the_samples_once_in_order(count, size):
    ranges = chunks(count, size)
    assert [i for r in ranges for i in r] == list(range(count))
    assert all(len(r) == size for r in ranges[:-1]) and 1 <= len(ranges[-1]) <= size


def test_chunks_split_as_stated():
    assert chunks(10, 4) == [range(0, 4), range(4, 8), range(8, 10)]
    assert chunks(3, 5) == [range(0, 3)]


class _Threads:
    """A stand-in for a Dask client: its cluster's threads, per worker."""

    def __init__(self, *threads):
        self.threads = threads

    def nthreads(self):
        return {f"worker {i}": n for i, n in enumerate(self.threads)}

    def submit(self, *args):
        raise AssertionError("nothing is sent")


@pytest.mark.parametrize("count", [0, 1, 7, 8, 9, 100])
def test_client_shares_cover_the_items_once_in_order_four_for_each_thread(count):
    items = list(range(count))
    shares = sweeps.client_shares(items, _Threads(1, 1))
    assert [item for share in shares for item in share] == items
    assert len(shares) <= 8 and all(shares)
    if count >= 8:
        assert len(shares) >= 5  # within a share's rounding of 4 x 2 threads
    with pytest.raises(TypeError, match="client must be a Dask client"):
        sweeps.client_shares(items, object())


_NOT_WHOLE = st.floats().filter(lambda x: not (math.isfinite(x) and x.is_integer()))


@given(value=st.one_of(_NOT_WHOLE, st.text(), st.booleans(), st.none()))
def test_chunks_refuse_anything_but_whole_numbers(value):
    with pytest.raises((TypeError, ValueError), match="count must be (a whole number|finite)"):
        chunks(value, 3)
    with pytest.raises((TypeError, ValueError), match="size must be (a whole number|finite)"):
        chunks(3, value)
    assert chunks(4.0, 3) == chunks(4, 3)  # a whole float is its number


def test_chunks_refuse_nothing_to_split():
    with pytest.raises(ValueError, match=r"count must lie in \[1, inf\]; got 0"):
        chunks(0, 3)
    with pytest.raises(ValueError, match=r"size must lie in \[1, inf\]; got -2"):
        chunks(10, -2)


@pytest.mark.parametrize("method", sweeps.SAMPLING_METHODS)
def test_uneven_chunks_concatenated_are_the_single_draw(method):
    bounds = [0, 1, 7, 8, 333, 1000, 1024, 3001]  # uneven, odd, a power of 2 and past it
    whole = sample_chunk(SEED, 3, range(3001), method)
    parts = [sample_chunk(SEED, 3, range(a, b), method) for a, b in itertools.pairwise(bounds)]
    assert whole.shape == (3001, 3)
    assert np.array_equal(np.concatenate(parts), whole)
    assert whole.min() >= 0 and whole.max() < 1
    assert not np.array_equal(sample_chunk(SEED + 1, 3, range(3001), method), whole)


def test_random_is_numpys_philox_draw():
    generator = np.random.Generator(np.random.Philox(key=SEED))
    assert np.array_equal(sample_chunk(SEED, 5, range(100), "random"), generator.random((100, 5)))


def test_sobol_chunks_keep_the_balance_of_the_whole_sample():
    """The first 2^m points of a (scrambled) Sobol' sequence put exactly one point in each of
    the 2^m equal intervals of every coordinate, even when drawn in chunks."""
    points = np.concatenate([sample_chunk(SEED, 6, r) for r in chunks(1024, 100)])
    bins = np.floor(points * 1024).astype(int)
    assert all(sorted(column) == list(range(1024)) for column in bins.T)


def test_bad_sample_arguments_are_named():
    with pytest.raises(ValueError, match=r"seed must lie in \[0, inf\]"):
        sample_chunk(-1, 2, range(3))
    with pytest.raises(TypeError, match="dimensions must be a whole number"):
        sample_chunk(1, "2", range(3))
    with pytest.raises(ValueError, match="indices must be a range"):
        sample_chunk(1, 2, range(0, 10, 2))
    with pytest.raises(ValueError, match="indices must be a range"):
        sample_chunk(1, 2, [0, 1, 2])
    with pytest.raises(ValueError, match="unknown method 'halton'"):
        sample_chunk(1, 2, range(3), "halton")


# On a Dask cluster: two worker processes, one thread each. The tests share one cluster, so
# they are kept in one pytest-xdist worker (run with --dist loadgroup).

on_cluster = pytest.mark.xdist_group("dask_cluster")


@pytest.fixture(scope="module")
def client():
    with (
        LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",  # any free port: two clusters may run at once
            silence_logs=logging.CRITICAL,
        ) as cluster,
        Client(cluster) as client,
    ):
        yield client


@on_cluster
def test_a_seeded_monte_carlo_is_the_same_on_the_cluster(client):
    items = chunks(20_000, 1_500)
    for method in sweeps.SAMPLING_METHODS:
        draw = partial(sample_chunk, SEED, 3, method=method)
        here, there = sweep(draw, items), sweep(draw, items, client=client)
        assert len(there) == len(items)
        assert all(np.array_equal(a, b) for a, b in zip(here, there, strict=True))
    reduced = partial(moments, SEED, 3)
    fold = {"reduce": operator.add, "initial": np.zeros(7)}
    here = sweep(reduced, items, **fold)
    assert np.array_equal(sweep(reduced, items, client=client, window=3, **fold), here)


@on_cluster
def test_the_cluster_folds_in_the_items_order(client):
    items = [5, 3, 9, 1, 7, 0, 2]
    assert sweep(abs, items, client=client) == items
    assert sweep(abs, items, client=client, reduce=order_sensitive, initial=0) == int(
        "005003009001007000002"
    )


@on_cluster
def test_the_cluster_pulls_at_most_a_window_of_items_ahead(client):
    stream = CountingItems()
    with pytest.raises(StopFolding):
        sweep(abs, stream, client=client, window=3, reduce=partial(folds_until, 40, stream, 3),
              initial=0)  # fmt: skip
    assert 40 <= stream.pulled <= 43


@on_cluster
def test_equal_items_are_distinct_tasks(client):
    assert len(set(sweep(fresh_random_number, [0] * 6, client=client))) == 6


@on_cluster
def test_an_error_on_the_cluster_names_the_item_that_raised(client):
    with pytest.raises(ArithmeticError, match="three") as raised:
        sweep(fail_on_three, range(6), client=client)
    assert "raised by item 3 of the sweep" in raised.value.__notes__


@on_cluster
def test_a_worker_killed_mid_sweep_loses_and_duplicates_no_sample(client):
    """One worker process is killed after the fifth result is folded; the scheduler reruns its
    task elsewhere, and its nanny starts a new worker. Every chunk is folded exactly once and
    the samples are those drawn in this process."""
    victim = next(iter(client.run(os.getpid).values()))
    folded = Counter()

    def fold(state, result):
        start, points = result
        folded[start] += 1
        if folded.total() == 5:
            os.kill(victim, signal.SIGKILL)
        return [*state, points]

    items = chunks(300, 10)
    samples = sweep(slow_chunk, items, client=client, reduce=fold, initial=[])
    assert folded == Counter(r.start for r in items)  # every chunk, once
    assert np.array_equal(np.concatenate(samples), sample_chunk(SEED, 2, range(300), "random"))
    client.wait_for_workers(2, timeout=30)
    assert victim not in client.run(os.getpid).values()  # the worker did die mid-sweep


@on_cluster
def test_a_raid_and_its_verification_are_the_same_on_the_cluster(client):
    from harp_analysis.analyses import fire_control
    from harp_analysis.analyses.fire_control.firing import BARBADOS_HP

    gun = BARBADOS_HP
    raid = fire_control.raid(gun, 3)
    here = fire_control.raid_windows(gun, raid, count=8)
    there = fire_control.raid_windows(gun, raid, count=8, client=client)
    assert [w.intercepts for w in here] == [w.intercepts for w in there]
    pairs = fire_control.raid_roots(here)
    assert pairs, "the small raid has feasible intercepts"
    aims, roots = [item.aim for item, _ in pairs], [root for _, root in pairs]
    local = fire_control.verify_with_3dof(gun, aims, roots, tolerance_m=1.0)
    remote = fire_control.verify_with_3dof(gun, aims, roots, tolerance_m=1.0, client=client)
    np.testing.assert_equal(
        [dataclasses.astuple(v) for v in remote], [dataclasses.astuple(v) for v in local]
    )
