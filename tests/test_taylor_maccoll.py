"""Taylor-Maccoll cone flow and the drag law of eq 4.8 (Chapter 4 B, Appendix C)."""

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from harp_analysis.models.drag import BASELINE_CONE, ExponentialDragLaw
from harp_analysis.models.taylor_maccoll import (
    BASELINE_HALF_ANGLE_RAD,
    EQ_4_8_MACH_GRID,
    TRAJECTORY_MACH_RANGE,
    ConeFlow,
    cone_drag_coefficient,
    cone_flow,
    fit_eq_4_8,
)

PUBLISHED = Path(__file__).parent / "reference" / "cone_flow_published.csv"


@pytest.fixture(scope="module")
def baseline_flow():
    return cone_flow(EQ_4_8_MACH_GRID, BASELINE_HALF_ANGLE_RAD)


def _cd(flow, normalisation):
    speed_term = flow.mach**2 + (5.0 if normalisation == "appendix_c" else 0.0)
    return (flow.surface_pressure_ratio - 0.75) / (0.7 * speed_term)


# --- independent check: NASA SP-3004 (Sims 1964) ------------------------------------------


def test_cone_flow_matches_nasa_sp3004_tables():
    table = pd.read_csv(PUBLISHED, comment="#")
    flow = cone_flow(table.mach.to_numpy(), np.radians(table.cone_half_angle_deg.to_numpy()))
    for name in ("shock_angle_rad", "surface_mach", "surface_pressure_ratio"):
        np.testing.assert_allclose(getattr(flow, name), table[name], rtol=1e-4, err_msg=name)


# --- limits and similarity -----------------------------------------------------------------


def test_slender_cone_limit_mach_angle_and_slender_body_pressure():
    mach = 3.0
    mach_angle, beta = math.asin(1.0 / mach), math.sqrt(mach**2 - 1.0)
    half_angles = np.radians([4.0, 2.0, 1.0])
    flow = cone_flow(mach, half_angles)
    excess = flow.shock_angle_rad - mach_angle
    assert np.all(excess > 0.0) and excess[-1] < 1e-5
    np.testing.assert_allclose(excess[:-1] / excess[1:], 16.0, rtol=0.1)  # shock strength ~ theta^4
    slender = half_angles**2 * (2.0 * np.log(2.0 / (beta * half_angles)) - 1.0)
    ratio = flow.pressure_coefficient / slender
    assert np.all(np.diff(ratio) < 0.0) and abs(ratio[-1] - 1.0) < 0.02
    assert np.all(np.diff(flow.pressure_coefficient) < 0.0)


@pytest.mark.parametrize("similarity", [0.5, 1.0, 2.0])
def test_hypersonic_similarity(similarity):
    half_angles = np.radians([2.0, 4.0])
    flow = cone_flow(similarity / half_angles, half_angles)
    scaled = flow.pressure_coefficient / half_angles**2
    assert scaled[1] == pytest.approx(scaled[0], rel=0.01)


def test_scalar_and_array_shapes():
    scalar = cone_flow(6.0, BASELINE_HALF_ANGLE_RAD)
    assert isinstance(scalar, ConeFlow) and isinstance(scalar.shock_angle_rad, float)
    grid = cone_flow([[5.0, 6.0]], BASELINE_HALF_ANGLE_RAD)
    assert grid.surface_mach.shape == (1, 2)
    assert grid.surface_pressure_ratio[0, 1] == pytest.approx(scalar.surface_pressure_ratio)


# --- drag coefficient and eq 4.8 -----------------------------------------------------------


def test_cd_falls_with_mach_over_the_trajectories():
    mach = np.linspace(*TRAJECTORY_MACH_RANGE, 5)
    for normalisation in ("free_stream", "appendix_c"):
        assert np.all(np.diff(cone_drag_coefficient(mach, normalisation=normalisation)) < 0.0)


def test_cd_definitions():
    mach = np.array([3.0, 6.0])
    physical = cone_drag_coefficient(mach)
    appendix_c = cone_drag_coefficient(mach, normalisation="appendix_c")
    np.testing.assert_allclose(physical / appendix_c, (mach**2 + 5.0) / mach**2)
    flow = cone_flow(mach, BASELINE_HALF_ANGLE_RAD)
    np.testing.assert_allclose(physical, flow.pressure_coefficient + 0.25 / (0.7 * mach**2))
    assert cone_drag_coefficient(6.0, base_pressure_ratio=1.0) == pytest.approx(
        flow.pressure_coefficient[1]
    )


def test_appendix_c_normalisation_reproduces_eq_4_8(baseline_flow):
    cd = _cd(baseline_flow, "appendix_c")
    fit = fit_eq_4_8(EQ_4_8_MACH_GRID, cd)
    # within one unit of the last digit eq 4.8 prints
    assert abs(fit.a - 0.077) <= 1e-3 and abs(fit.b + 0.38) <= 1e-2 and abs(fit.c - 0.014) <= 1e-3
    assert fit.r_squared >= 0.999
    inside = EQ_4_8_MACH_GRID <= 10.0
    np.testing.assert_allclose(cd[inside], BASELINE_CONE(EQ_4_8_MACH_GRID[inside]), rtol=0.02)


def test_physical_cd_does_not_reproduce_eq_4_8(baseline_flow):
    fit = fit_eq_4_8(EQ_4_8_MACH_GRID, _cd(baseline_flow, "free_stream"))
    assert fit.b < -0.6 and fit.a > 0.3
    launch = _cd(baseline_flow, "free_stream")[EQ_4_8_MACH_GRID == 6.5][0]
    assert launch / BASELINE_CONE(6.5) > 1.1  # 12 % above eq 4.8 near the launch Mach


def test_fit_recovers_known_coefficients():
    mach = np.linspace(2.0, 10.0, 17)
    fit = fit_eq_4_8(mach, 0.05 * np.exp(-0.3 * mach) + 0.02)
    assert (fit.a, fit.b, fit.c) == pytest.approx((0.05, -0.3, 0.02), rel=1e-6)
    assert fit.r_squared == pytest.approx(1.0)
    assert isinstance(fit.law, ExponentialDragLaw) and fit.law(4.0) == pytest.approx(
        0.05 * math.exp(-1.2) + 0.02
    )


# --- bad input -----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "mach, half_angle, name",
    [
        (float("nan"), 0.1, "mach"),
        (1.0, 0.1, "mach"),
        ([3.0, 0.5], 0.1, "mach"),
        (3.0, float("nan"), "half_angle_rad"),
        (3.0, 0.0, "half_angle_rad"),
        (3.0, -0.1, "half_angle_rad"),
        (3.0, math.pi / 2, "half_angle_rad"),
        (1.5, math.radians(35.0), "mach"),  # detached: about 30.6 deg is the largest
        (2.0, math.radians(41.0), "mach"),  # detached: about 40.7 deg is the largest
        (2.0, math.radians(0.3), "half_angle_rad"),  # too slender to resolve
    ],
)
def test_bad_cone_flow_input_names_argument(mach, half_angle, name):
    with pytest.raises(ValueError, match=name):
        cone_flow(mach, half_angle)


def test_bad_drag_and_fit_input_names_argument():
    with pytest.raises(ValueError, match="normalisation"):
        cone_drag_coefficient(5.0, normalisation="dynamic")
    with pytest.raises(ValueError, match="base_pressure_ratio"):
        cone_drag_coefficient(5.0, base_pressure_ratio=float("nan"))
    with pytest.raises(ValueError, match="gamma"):
        cone_flow(5.0, 0.1, gamma=1.0)
    with pytest.raises(ValueError, match="cd"):
        fit_eq_4_8([2.0, 3.0, 4.0, 5.0], [0.1, 0.2])
    with pytest.raises(ValueError, match="mach_grid"):
        fit_eq_4_8([2.0, float("inf"), 4.0, 5.0], [0.1, 0.2, 0.3, 0.4])
