"""The one sweep: results in the items' order, in process (bar or none) or on a Dask client."""

import operator
from functools import partial

import pytest

from harp_analysis import sweeps


class FakeClient:
    """Dask's client as the sweep uses it: map returns futures, gather their results. It
    finishes the futures in reverse order, as a cluster may, and records the calls."""

    def __init__(self):
        self.calls = []

    def map(self, function, items):
        self.calls.append(("map", len(items)))
        return [("future", function, item) for item in items]

    def gather(self, futures):
        self.calls.append(("gather", len(futures)))
        done = {id(f): f[1](f[2]) for f in reversed(futures)}
        return [done[id(f)] for f in futures]


def test_results_come_in_the_items_order():
    items = [5, 3, 9, 1, 7]
    assert sweeps.sweep(partial(operator.mul, 2), items, progress=False) == [10, 6, 18, 2, 14]
    assert sweeps.sweep(str, iter(range(4)), progress=False) == ["0", "1", "2", "3"]
    assert sweeps.sweep(str, [], progress=False) == []


def test_no_bar_when_progress_is_off_or_nobody_watches(monkeypatch, capsys):
    monkeypatch.setattr(sweeps, "interactive", lambda: True)
    assert sweeps.sweep(abs, [-1, -2], progress=False, description="quiet") == [1, 2]
    assert "quiet" not in capsys.readouterr().err
    monkeypatch.setattr(sweeps, "interactive", lambda: False)
    assert sweeps.sweep(abs, [-1, -2], description="headless") == [1, 2]
    assert "headless" not in capsys.readouterr().err


def test_the_bar_shows_when_someone_watches(monkeypatch, capsys):
    monkeypatch.setattr(sweeps, "interactive", lambda: True)
    assert sweeps.sweep(abs, [-3, 4, -5], description="watched") == [3, 4, 5]
    assert "watched" in capsys.readouterr().err


def test_interactive_follows_the_terminal_and_the_jupyter_server(monkeypatch):
    monkeypatch.delenv("JPY_SESSION_NAME", raising=False)
    assert sweeps.interactive() is False  # pytest captures standard error: not a terminal
    monkeypatch.setenv("JPY_SESSION_NAME", "notebook.ipynb")
    assert sweeps.interactive() is True


def test_a_client_runs_the_sweep_through_map_and_gather():
    client = FakeClient()
    items = [4, 1, 3, 2]
    assert sweeps.sweep(partial(operator.pow, 2), items, client=client) == [16, 2, 8, 4]
    assert client.calls == [("map", 4), ("gather", 4)]


def test_bad_function_or_client_is_named():
    with pytest.raises(TypeError, match="function must be callable"):
        sweeps.sweep(3, [1])
    with pytest.raises(TypeError, match="client must be a Dask client.*has no map or gather"):
        sweeps.sweep(abs, [1], client=object())
