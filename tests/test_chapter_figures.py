"""The figures of Chapters 2-4 (notebooks 01-04), each drawn by one function of
reporting/figures: every one 6.5 in wide with the axes and the series its dissertation figure
has. The atmosphere's and the Modified Kepler equation's figures are drawn from the package's own
models and flights and must pass the figure lint as saved; the reference trajectories' from
constructed flights (the notebooks draw and lint the real ones, and tests/test_figure_images.py
holds every one to its committed image)."""

import matplotlib

matplotlib.use("agg")

import warnings

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest

from harp_analysis.analyses import comparisons
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models.launch import HP_CHAPTER_2, LP_CHAPTER_2, baseline_chapter_4
from harp_analysis.reporting import plotting
from harp_analysis.reporting.figures import (
    atmosphere,
    mks_vs_simulation,
    modified_kepler,
    reference_trajectories,
)
from harp_analysis.reporting.plotting import FULL_WIDTH_IN


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


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


def _flight(name, model):
    """A constructed flight of projectile ``name`` by ``model``: up to 40 km at 50 s; HP's MLT
    swerves kilometres, the others metres; the drag coefficient bumps at 60 s."""
    launch = HP_CHAPTER_2 if name == "HP" else LP_CHAPTER_2
    t = np.linspace(0.0, 100.0, 201)
    altitude = 40e3 * (1.0 - ((t - 50.0) / 50.0) ** 2)
    swerve = {"3DOF": 0.0, "6DOF": 2.0 + (name == "LP"), "MLT": 3.0 if name == "LP" else 50.0}
    flight = pd.DataFrame(
        {"time_s": t, "ground_range_m": 1000.0 * t, "altitude_m": altitude,
         "cross_range_m": 5.0 * t + swerve[model] * t, "speed_m_s": 2000.0 - 10.0 * t,
         "angle_of_attack_rad": 0.002 * t, "mach": 6.0 - 0.03 * t,
         "drag_coefficient": 0.3 + np.exp(-(((t - 60.0) / 5.0) ** 2)),
         "specific_angular_momentum_m2_s": 1e8 - 1e5 * t,
         "drag_to_gravity": 20.0 * np.exp(-altitude / 5e3)}
    )  # fmt: skip
    flight.attrs = {"apogee_time_s": 50.0, "launch": launch}
    return flight


FLIGHTS = {(name, model): _flight(name, model)
           for model in ("3DOF", "6DOF", "MLT") for name in ("HP", "LP")}  # fmt: skip
SPHERICAL = {name: _flight(name, "6DOF") for name in ("HP", "LP")}
EVERY_FLIGHT = ["HP 3DOF", "LP 3DOF", "HP 6DOF", "LP 6DOF", "HP MLT", "LP MLT"]
TRUE_ALTITUDE = "6DOF, air at the true altitude"


@pytest.mark.parametrize(
    ("draw", "arguments", "labels"),
    [
        ("draw_cross_range", (FLIGHTS,), EVERY_FLIGHT),
        ("draw_speed", (FLIGHTS, SPHERICAL), [*EVERY_FLIGHT, TRUE_ALTITUDE]),
        ("draw_angle_of_attack", (FLIGHTS,), EVERY_FLIGHT[2:]),
        ("draw_range_against_time", (FLIGHTS,), EVERY_FLIGHT),
        ("draw_angular_momentum", (FLIGHTS, SPHERICAL), [*EVERY_FLIGHT[:4], TRUE_ALTITUDE]),
    ],
)
def test_one_panel_figures_figs_2_3_to_2_6_and_2_10(draw, arguments, labels):
    (ax,) = _drawn(getattr(reference_trajectories, draw)(*arguments), 1)
    assert _labels(ax) == labels


def test_altitude_with_drag_ratio_fig_2_2_marks_each_crossing():
    (ax,) = _drawn(reference_trajectories.draw_altitude_with_drag_ratio(FLIGHTS), 1)
    assert _labels(ax) == EVERY_FLIGHT
    marks = [text.get_text() for text in ax.texts]  # N falls to 0.007 at the 40 km apogee
    assert marks == 2 * [f"$N$ = {ratio:g}" for ratio in (10, 1, 0.1, 0.01)]


def test_swerve_fig_2_7_marks_hp_mlt_off_the_detail_scale():
    top, bottom = _drawn(reference_trajectories.draw_swerve(FLIGHTS), 2)
    assert _labels(top) == ["HP 6DOF", "LP 6DOF", "HP MLT", "LP MLT"]
    assert [text.get_text() for text in bottom.texts] == ["HP MLT: off scale (upper panel)"]
    assert bottom.get_ylim()[1] < top.get_ylim()[1]


def test_mach_and_drag_fig_2_8_marks_the_yaw_drag():
    top, bottom = _drawn(reference_trajectories.draw_mach_and_drag(FLIGHTS, SPHERICAL), 2)
    assert _labels(top) == [*EVERY_FLIGHT[:4], TRUE_ALTITUDE]
    (note,) = bottom.texts
    assert note.get_text().startswith("HP 6DOF: yaw drag") and note.xy[0] == pytest.approx(60.0)


def test_lower_atmosphere_fig_2_9_draws_the_height_over_the_launch_line():
    above, below = _drawn(reference_trajectories.draw_lower_atmosphere(FLIGHTS), 2)
    assert _labels(above) == ["HP 3DOF", "HP 6DOF", "LP 3DOF", "LP 6DOF", "straight line at 50°"]
    assert len(below.get_lines()) == 5  # the four flights and the line itself, at zero
    x_km, height_m = below.get_lines()[0].get_data()
    altitude_m = 40e3 * (1.0 - ((x_km - 50.0) / 50.0) ** 2)
    assert x_km.max() < 50.0 and altitude_m.max() < 20e3  # the ascent below 20 km
    assert np.allclose(height_m, altitude_m - np.tan(np.radians(50.0)) * x_km * 1e3)


def test_polar_coordinates_fig_3_1():
    whole, near = _drawn(modified_kepler.draw_polar_coordinates(baseline_chapter_4(45.0)), 2)
    assert whole.get_title() == "(a) about the Earth's centre O"
    assert _labels(near) == ["MKS, baseline at 45°"]
    assert plotting.figure_defects(whole.figure) == []


def test_straight_line_fig_3_3():
    (ax,) = _drawn(modified_kepler.draw_straight_line(baseline_chapter_4(45.0)), 1)
    assert _labels(ax) == ["3DOF", "MKS", r"$a = \theta\, r_0 \tan\phi_0$ (eq 3.16)"]
    assert max(ax.get_lines()[0].get_ydata()) < 40.0  # the 3DOF's ascent below 40 km
    assert plotting.figure_defects(ax.figure) == []


def test_frequency_response_fig_3_4_marks_the_driving_rates():
    with pytest.warns(UserWarning):  # HP's beta exceeds the MKS's validity, as in the text
        (ax,) = _drawn(modified_kepler.draw_frequency_response(HP_CHAPTER_2), 1)
    labels = _labels(ax)
    assert labels[0] == r"linearised (eq 3.30), $\omega_n = 1$" and "eq 3.29" in labels[1]
    assert [text.get_text() for text in ax.texts] == [r"$\tau$", r"$2\tau$", r"$3\tau$"]
    assert plotting.figure_defects(ax.figure) == []


HP_50 = comparisons.chapter_4_launch("HP", 50.0)
ELEVATIONS = (30.0, 45.0, 65.0, 85.0)
ELEVATION_NAMES = ["30 deg", "45 deg", "65 deg", "85 deg"]


@pytest.fixture
def quiet_mks():
    """HP's beta exceeds the MKS's validity, as the text knows: the warning is not the test's."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        yield


def test_error_geometry_fig_4_5(quiet_mks):
    (ax,) = _drawn(mks_vs_simulation.draw_error_geometry(HP_50), 1)
    assert ax.get_title().startswith("HP at apogee")
    labels = _labels(ax)
    assert labels[0].startswith(r"MKS at $\theta_i$") and labels[1:] == [
        r"3DOF at $t_i$",
        r"MKS at $t_i$",
    ]
    notes = [text.get_text() for text in ax.texts if text.get_text()]
    assert [note.split(" = ")[0] for note in notes] == [
        r"$\varepsilon_r$",
        r"$\varepsilon_\theta$",
        "total, eq 4.7",
    ]
    assert plotting.figure_defects(ax.figure) == []


def test_error_by_terms_fig_4_6(quiet_mks):
    left, right = _drawn(mks_vs_simulation.draw_error_by_terms(HP_50), 2)
    assert _labels(left) == ["1 term", "2 terms", "3 terms", "4 terms", "5 terms"]
    assert _labels(right) == ["eq 4.7, geometric", "eqs 4.6-4.7, printed", "direct, equal time"]
    assert left.get_ylim() == right.get_ylim() == (0.0, 8.0)
    assert plotting.figure_defects(left.figure) == []


def _effort_table():
    methods = ["6DOF", "3DOF", "MLT", "MKS (3 terms)", "MKS, a million launches at once"]
    return pd.DataFrame(
        {"flops": [1e9, 1e7, 1e6, 300.0, 300.0], "seconds": [2.0, 0.1, 0.05, 1e-5, 1e-7],
         "apogee_difference_m": [0.0, 50.0, 200.0, 3000.0, 3000.0]},
        index=pd.Index(methods, name="method"),
    )  # fmt: skip


@pytest.mark.parametrize(
    ("draw", "points"), [("draw_effort", 4), ("draw_wall_time", 5)], ids=["fig_4_7", "wall_time"]
)
def test_effort_puts_the_reference_in_a_slot_of_its_own(draw, points):
    (ax,) = _drawn(getattr(mks_vs_simulation, draw)(_effort_table()), 1)
    assert len(ax.get_lines()) == points
    assert ax.texts[0].get_text() == "6DOF: reference (0 m)"
    assert ax.get_lines()[0].get_xdata()[0] == 0.15  # left of the break, ticked "0"
    assert ax.xaxis.get_major_formatter()(0.15, 0) == "0"


def test_three_projectiles_fig_4_8():
    (ax,) = _drawn(mks_vs_simulation.draw_three_projectiles(50.0), 1)
    assert _labels(ax) == [f"{name}, {model}" for name in ("HP", "LP", "baseline")
                           for model in ("3DOF", "MKS")]  # fmt: skip


def test_cone_drag_fig_4_9():
    (ax,) = _drawn(mks_vs_simulation.draw_cone_drag(), 1)
    labels = _labels(ax)
    assert labels[2].startswith("eq 4.8 (text)") and labels[3].startswith("fit: ")
    assert plotting.figure_defects(ax.figure) == []


@pytest.mark.parametrize(
    "draw",
    ["draw_baseline_trajectories", "draw_straight_lines", "draw_drag_coefficient_against_altitude"],
)
def test_baseline_elevations_figs_4_10_4_14_4_16_label_every_curve(draw):
    (ax,) = _drawn(getattr(mks_vs_simulation, draw)(ELEVATIONS), 1)
    assert [text.get_text() for text in ax.texts if "deg" in text.get_text()] == ELEVATION_NAMES
    assert plotting.figure_defects(ax.figure) == []


def test_asymptotic_momentum_error_fig_4_12():
    (ax,) = _drawn(mks_vs_simulation.draw_asymptotic_momentum_error((30.0, 60.0)), 1)
    assert list(ax.get_lines()[0].get_xdata()) == [30.0, 60.0]
