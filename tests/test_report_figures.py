"""What the figures of Chapters 5-6 and the project's extensions show, on constructed inputs:
each drawn 6.5 in wide with nothing outside it, Fig 5.4-5.9's labels beside their own curves,
Figure X.3's zeros and input sizes, X.5's open-marker rule in both panels, X.6's launches
beyond the MKS's validity and X.7's sign where the improved MKS is farther."""

import matplotlib

matplotlib.use("agg")

import numpy as np
import pandas as pd
import pytest
from matplotlib.lines import Line2D

from harp_analysis.analyses import error_budget
from harp_analysis.reporting.figures import error_budget as budget_figures
from harp_analysis.reporting.figures import rotating_earth
from harp_analysis.reporting.plotting import FULL_WIDTH_IN, new_figure


def _fits_the_page(fig):
    """The figure is 6.5 in wide and everything drawn lies inside it (nothing a fixed-size
    save would cut off)."""
    fig.canvas.draw()
    width, height = fig.get_size_inches()
    drawn = fig.get_tightbbox()
    assert width == FULL_WIDTH_IN
    assert drawn.x0 >= 0 and drawn.y0 >= 0 and drawn.x1 <= width and drawn.y1 <= height


def _markers(ax, marker):
    return [
        line for line in ax.get_lines() if line.get_marker() == marker and len(line.get_xdata())
    ]


def test_labels_sit_beside_their_own_curves():
    """Two crossing curves: each label's box crosses no curve, and its own curve is nearer
    than the other by far (a label cannot be read as the other's)."""
    fig, ax = new_figure()
    x = np.linspace(0.0, 10.0, 200)
    lines = [ax.plot(x, x)[0], ax.plot(x, 10.0 - x)[0]]
    ax.set_xlim(0, 10)
    ax.set_ylim(0, 10)
    fig.canvas.draw()
    texts = rotating_earth.label_beside_curves(ax, lines, ["rising", "falling"])
    renderer = fig.canvas.get_renderer()
    for text, own, other in zip(texts, lines, lines[::-1]):
        box = text.get_window_extent(renderer)
        for line in lines:
            path = line.get_transform().transform_path(line.get_path())
            assert not path.intersects_bbox(box, filled=False)
        px, py = text.get_position()
        near_own = np.min(np.hypot(own.get_xdata() - px, own.get_ydata() - py))
        near_other = np.min(np.hypot(other.get_xdata() - px, other.get_ydata() - py))
        assert near_own < 0.5 * near_other


def test_off_scale_mark_is_no_elevation_marker():
    """Fig 5.5's clash: the mark where a curve leaves the axis had the 65 deg curve's triangle."""
    from harp_analysis.analyses.rotating import ELEVATIONS_DEG
    from harp_analysis.reporting.plotting import elevation_style

    markers = {elevation_style(e, ELEVATIONS_DEG)["marker"] for e in ELEVATIONS_DEG}
    assert rotating_earth._OFF_SCALE["marker"] not in markers | {"*"}


def test_input_sizes_are_printed_in_a_readers_unit():
    sizes = {u.name: budget_figures.size_label(u) for u in error_budget.CHAPTER_7B}
    assert sizes["elevation"] == "elevation, 1 mrad"  # Ch. 7 B's "milli-radian"
    assert sizes["latitude"] == "latitude, 1 arcsec"
    assert sizes["muzzle speed"] == "muzzle speed, 3.05 m/s"  # 10 ft/s
    assert sizes["fire time"] == "fire time, 1 ms"
    assert sizes["air density"] == "air density, 2 %"


def _budget_inputs():
    names = [u.name for u in error_budget.CHAPTER_7B]
    launches = ("HP, 50 deg", "baseline, 45 deg")
    inputs = {}
    for k, launch in enumerate(launches):
        table = pd.DataFrame(
            {"impact_m": np.linspace(10.0, 900.0, len(names)) * (k + 1),
             "position_m": np.linspace(5.0, 400.0, len(names))},
            index=pd.Index(names, name="input"),
        )  # fmt: skip
        table.loc["fire time", "impact_m"] = 0.0  # the Earth-fixed impact point cannot move
        inputs[launch] = table
    index = pd.MultiIndex.from_product([launches, ("impact", "position")])
    budget = pd.DataFrame({"dispersion_m": 2000.0, "mks_error_m": 1500.0}, index=index)
    return inputs, budget


def test_error_budget_shows_zeros_at_the_axis_edge_and_the_sizes():
    inputs, budget = _budget_inputs()
    fig = budget_figures.draw_error_budget(inputs, budget)
    _fits_the_page(fig)
    impact = fig.axes[0]
    labels = [t.get_text() for t in impact.get_yticklabels()]
    assert labels[0] == "elevation, 1 mrad"
    row = labels.index("fire time, 1 ms")
    left = impact.get_xlim()[0]
    zeros = []
    for line in impact.get_lines():
        x, y = np.asarray(line.get_xdata()), np.asarray(line.get_ydata())
        near = np.abs(y - row) < 0.45
        zeros += list(x[near])
    assert len(zeros) == len(inputs)  # one marker per launch, none dropped
    zero_at = zeros[0]
    assert np.allclose(zeros, zero_at) and left < zero_at < 10.0 / 1e3  # a decade below 10 m
    tick_labels = [impact.xaxis.get_major_formatter()(v, 0) for v in impact.get_xticks()]
    assert "0" in tick_labels


def test_harp_confidence_opens_every_marker_whose_interval_holds_zero():
    residuals = pd.DataFrame(
        {"estimate_m": [-800.0, 2200.0], "low_m": [-1700.0, 1900.0], "high_m": [60.0, 2700.0]},
        index=pd.MultiIndex.from_tuples([("barbados", "mean"), ("barbados", "std")]),
    )
    transfers = pd.DataFrame(
        {"fit_site": ["barbados", "yuma"], "predict_site": ["yuma", "barbados"],
         "densities": ["site", "temperature"], "mean_residual_m": [1000.0, -5000.0],
         "mean_residual_m_low": [-100.0, -6000.0], "mean_residual_m_high": [2500.0, -4000.0],
         "holds": [True, False]}
    )  # fmt: skip
    fig = budget_figures.draw_harp_confidence(residuals, transfers, {"barbados": 2.25}, {})
    _fits_the_page(fig)
    for ax, open_rows in zip(fig.axes[:2], ([0], [0])):
        points = [line for line in ax.get_lines() if line.get_marker() in "osD^"]
        points = [p for p in points if p.get_color() != "#7F7F7F"]
        faces = {int(p.get_ydata()[0]): p.get_markerfacecolor() for p in points}
        assert [y for y, face in faces.items() if face == "white"] == open_rows
    assert fig.legends and len(fig.legends[0].get_texts()) == 6


def test_judged_marks_launches_beyond_the_mks_validity():
    rows = []
    for beta, elevation in ((0.2, 45.0), (0.4, 40.0)):
        for variant, error in (("dissertation", 3000.0), ("improved", 300.0)):
            rows.append(dict(projectile="LP", elevation_deg=elevation, latitude_deg=0.0,
                             bearing_deg=0.0, rotating=False, beta=beta, variant=variant,
                             max_error_m=error, impact_miss_m=error))  # fmt: skip
    fig = budget_figures.draw_judged(pd.DataFrame(rows))
    _fits_the_page(fig)
    ax = fig.axes[0]
    mks = _markers(ax, "o")
    open_rows = [
        y for line in mks if line.get_markerfacecolor() == "white" for y in line.get_ydata()
    ]
    assert open_rows == [1]
    labels = [t.get_text() for t in ax.get_yticklabels()]
    assert "0.40" in labels[1] and "beta" not in labels[0]


def test_error_maps_mark_the_sign_where_the_improved_mks_is_farther():
    """A 2 x 2 map: the improved MKS farther at (090T, 60 deg) only, unsolved at (0, 60 deg):
    one plus sign there, one dot, whatever the colours."""
    points = [(b, e) for e in (30.0, 60.0) for b in (0.0, 90.0)]
    improved = {(0.0, 30.0): 100.0, (90.0, 30.0): 200.0, (0.0, 60.0): np.nan, (90.0, 60.0): 900.0}
    frame = pd.DataFrame(
        [dict(bearing_deg=b, elevation_deg=e, latitude_deg=0.0, air_momentum_share=0.1,
              dissertation_impact_miss_m=500.0, improved_impact_miss_m=improved[(b, e)],
              dissertation_max_error_m=500.0, improved_max_error_m=improved[(b, e)])
         for b, e in points]
    )  # fmt: skip
    fig = budget_figures.draw_error_maps(frame, (-0.5, 1.0))
    _fits_the_page(fig)
    impact = fig.subfigs[0].axes[0]
    (plus,) = _markers(impact, "+")
    assert list(zip(plus.get_xdata(), plus.get_ydata())) == [(90.0, 60.0)]
    (dot,) = _markers(impact, "o")
    assert list(zip(dot.get_xdata(), dot.get_ydata())) == [(0.0, 60.0)]


@pytest.mark.parametrize("number", list(rotating_earth.SCHEMATICS))
def test_schematics_fit_the_page(number):
    from harp_analysis.engines import eci
    from harp_analysis.models.launch import baseline_chapter_4

    shot = baseline_chapter_4(45.0, rotation_rate_rad_s=7.292115e-5)
    correction = eci.correction_for_launch(shot)
    fig = rotating_earth.draw_launch_schematic(number, correction, shot.latitude_rad, "case")
    _fits_the_page(fig)
    assert all(isinstance(h, Line2D) for h in fig.legends[0].legend_handles)
