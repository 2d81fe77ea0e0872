"""The quantities of harp_analysis.analyses.claims.chapter7, checked against closed forms, the
vacuum and an independent 3DOF flight."""

import math

import numpy as np
import pytest

from harp_analysis.analyses.claims import chapter7
from harp_analysis.engines import threedof
from harp_analysis.models.launch import baseline_chapter_4


def test_late_arrival_miss_is_speed_times_delay_plus_the_gravity_drop():
    level = chapter7.late_arrival_miss_m(2000.0, 0.5, 0.0, 9.81)
    assert level == pytest.approx(math.hypot(1000.0, 9.81 * 0.125))
    vertical = chapter7.late_arrival_miss_m(2000.0, 0.5, 90.0, 9.81)
    assert vertical == pytest.approx(1000.0 - 9.81 * 0.125)


def test_firing_solutions_agree_and_hit_the_point():
    elevation_mks, _, _ = chapter7.firing_solution("mks")
    elevation_3dof, iterations, evaluations = chapter7.firing_solution("3dof")
    assert elevation_mks == pytest.approx(elevation_3dof, abs=0.1)  # the MKS's accuracy
    flight = threedof.simulate_3dof(baseline_chapter_4(elevation_3dof), output_step_s=0.1)
    up = flight[flight.time_s <= flight.attrs["apogee_time_s"]]
    assert np.interp(150e3, up.ground_range_m, up.altitude_m) == pytest.approx(100e3, abs=1.0)
    assert evaluations > 100 * iterations


def test_pointing_shift_in_a_vacuum_turns_the_velocity():
    launch = baseline_chapter_4(45.0, atmosphere="vacuum")
    shift = chapter7.position_shift_m(launch, elevation_error_mrad=1.0, at_s=10.0)
    assert shift == pytest.approx(2157.0 * 10.0 * 1e-3, rel=5e-3)
    speed_shift = chapter7.position_shift_m(launch, speed_error_m_s=1.0, at_s=10.0)
    assert speed_shift == pytest.approx(10.0, rel=5e-3)


def test_mks_lands_where_the_3dof_does_in_a_vacuum():
    assert chapter7.mks_impact_miss_km("baseline", 45.0, atmosphere="vacuum") < 1e-3


def test_the_corrected_angular_momentum_slows_the_error_s_growth():
    """Taking h_inf from the 3DOF's apogee removes the mismatch that drives the growth."""
    growth = chapter7.error_growth()
    assert growth.impact_over_apogee > 1.0
    assert growth.corrected_impact_over_apogee < growth.impact_over_apogee
    assert growth.corrected_impact_km < growth.impact_km
