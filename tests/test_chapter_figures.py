"""The figures of Chapters 2-4 (notebooks 01-04), each drawn by one function of
reporting/figures: every one 6.5 in wide with the axes and the series its dissertation figure
has. The atmosphere's figures are drawn from the models themselves and must pass the figure lint
as saved."""

import matplotlib

matplotlib.use("agg")

import numpy as np
import pytest

from harp_analysis.reporting import plotting
from harp_analysis.reporting.figures import atmosphere
from harp_analysis.reporting.plotting import FULL_WIDTH_IN


def _labels(ax):
    return [text.get_text() for text in ax.get_legend().get_texts()]


def _drawn(fig, panels):
    """``fig`` is a page wide and has ``panels`` axes."""
    assert fig.get_figwidth() == FULL_WIDTH_IN
    assert len(fig.axes) == panels
    return fig.axes


def test_density_models_fig_2_1():
    top, bottom = _drawn(atmosphere.draw_density_models(), 2)
    assert _labels(top) == [
        "US Standard Atmosphere 1976",
        "multi-stage model, eqs 2.1-2.2 (App. B)",
        "three-layer model (App. A)",
    ]
    assert len(bottom.get_lines()) == 3  # each model's error, and the zero line
    assert top.get_xlim()[1] == pytest.approx(105.0)  # to 100 km, with matplotlib's margin
    assert plotting.figure_defects(top.figure) == []


def test_exponential_model_fig_3_2():
    (ax,) = _drawn(atmosphere.draw_exponential_model(50.0), 1)
    labels = _labels(ax)
    assert labels[0] == "US Standard Atmosphere 1976" and "0.117" in labels[1]
    assert "(fit, $R^2$" in labels[2]
    assert plotting.figure_defects(ax.figure) == []


def test_r_squared_flatness_marks_the_texts_k_and_r_squared():
    (ax,) = _drawn(atmosphere.draw_r_squared_flatness(np.linspace(0.11, 0.12, 5)), 1)
    assert _labels(ax) == ["0-20 km", "0-50 km", "0-100 km", "text's $k$", "text's $R^2$"]
    assert all(len(line.get_xdata()) == 5 for line in ax.get_lines()[:3])
