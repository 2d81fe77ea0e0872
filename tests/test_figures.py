"""Figures are saved by number, deterministically: two regenerations are byte-identical."""

import hashlib

import numpy as np
import pytest

from harp_analysis import paths, plotting


@pytest.fixture
def figures_dir(tmp_path, monkeypatch):
    monkeypatch.setattr(paths, "FIGURES_DIR", tmp_path)
    return tmp_path


def _digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_save_figure_names_file_by_number_and_is_deterministic(figures_dir):
    fig, ax = plotting.new_figure()
    ax.plot(np.arange(10), np.arange(10) ** 2)
    first = _digest(plotting.save_figure(fig, "2.1"))
    second_path = plotting.save_figure(fig, "2.1")
    assert second_path == figures_dir / "fig_2_1.png"
    assert _digest(second_path) == first
    assert b"Software" not in second_path.read_bytes()
    assert b"tIME" not in second_path.read_bytes()  # no PNG time chunk


def test_save_figure_refuses_unregistered_or_fileless_numbers(figures_dir):
    fig, _ = plotting.new_figure()
    with pytest.raises(ValueError, match="'8.1'"):
        plotting.save_figure(fig, "8.1")
    with pytest.raises(ValueError, match="'1.1'.*no output file"):
        plotting.save_figure(fig, "1.1")
    with pytest.raises(TypeError, match="fig must be a matplotlib Figure"):
        plotting.save_figure("figure", "2.1")
