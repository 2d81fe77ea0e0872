"""Appendix A's own scheme: its artefacts are real, and it converges to the accurate 3DOF."""

import numpy as np
import pytest

from harp_analysis import appendix_a, threedof
from harp_analysis.projectiles import BASELINE


@pytest.fixture(scope="module")
def accurate():
    return threedof.simulate_3dof(BASELINE, 45.0, atmosphere="three_layer")


def test_clock_leads_position_by_one_step():
    dt = 0.1
    rows = appendix_a.simulate_appendix_a(BASELINE, 45.0, dt)
    first = rows.iloc[0]
    assert first.time_s == pytest.approx(3 * dt)
    # The first position is two steps out (Euler then one recurrence step), not three.
    two_steps = 2 * dt * 2157.0 * np.sin(np.radians(45.0))
    assert first.altitude_m == pytest.approx(two_steps, rel=0.01)


def test_launch_offset_against_an_accurate_solution(accurate):
    """Compared at the macro's clock, a 0.1 s step puts the launch rows ~200 m behind."""
    rows = appendix_a.simulate_appendix_a(BASELINE, 45.0, 0.1, max_time_s=5.0)
    truth = np.interp(rows.time_s, accurate.time_s, accurate.altitude_m)
    gap = truth - rows.altitude_m
    assert 0.9 * 0.1 * 2157 * np.sin(np.radians(45)) < gap.iloc[0] < 1.1 * 0.1 * 2157


def test_converges_to_the_accurate_3dof_at_first_order(accurate):
    errors = [
        abs(
            appendix_a.simulate_appendix_a(BASELINE, 45.0, dt).altitude_m.max()
            - accurate.attrs["apogee_altitude_m"]
        )
        for dt in (0.2, 0.1)
    ]
    assert errors[1] < 0.6 * errors[0]  # halving the step roughly halves the error
    assert errors[1] < 0.005 * accurate.attrs["apogee_altitude_m"]


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"dt_s": 0.0}, "dt_s"),
        ({"dt_s": np.nan}, "dt_s"),
        ({"elevation_deg": 95.0}, "elevation_deg"),
    ],
)
def test_bad_input_is_named(kwargs, name):
    arguments = {"elevation_deg": 45.0, "dt_s": 0.1} | kwargs
    with pytest.raises(ValueError, match=name):
        appendix_a.simulate_appendix_a(BASELINE, **arguments)
