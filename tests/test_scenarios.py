"""The reference flights' readings the figures draw, on constructed flights: the ascent below an
altitude, the straight launch line of eq 3.16 and a flight's height over it (Fig 2.9), where N =
drag/gravity falls through a ratio (Fig 2.2), and the 6DOF's yaw-drag peak (Fig 2.8)."""

import numpy as np
import pandas as pd
import pytest

from harp_analysis.analyses import scenarios
from harp_analysis.models.launch import HP_CHAPTER_2


def _flight(elevation_deg=50.0):
    """A flight climbing along its launch line and falling back: apogee 40 km at 50 s."""
    time_s = np.linspace(0.0, 100.0, 101)
    ground_range_m = 1000.0 * time_s
    altitude_m = 40e3 * (1.0 - ((time_s - 50.0) / 50.0) ** 2)
    flight = pd.DataFrame(
        {"time_s": time_s, "ground_range_m": ground_range_m, "altitude_m": altitude_m,
         "drag_to_gravity": 20.0 * np.exp(-altitude_m / 5e3),
         "drag_coefficient": 0.3 + np.exp(-(((time_s - 60.0) / 5.0) ** 2)) + (time_s > 95),
         "angle_of_attack_rad": time_s / 100.0}
    )  # fmt: skip
    flight.attrs = {"apogee_time_s": 50.0, "launch": HP_CHAPTER_2.but(elevation_deg=elevation_deg)}
    return flight


def test_ascent_below_keeps_the_way_up_under_the_altitude():
    low = scenarios.ascent_below(_flight(), 20e3)
    assert (low.altitude_m < 20e3).all() and (low.time_s <= 50.0).all()
    assert len(low) == int(np.sum((_flight().altitude_m < 20e3) & (_flight().time_s <= 50.0)))


def test_the_straight_line_is_eq_3_16_and_the_height_over_it_is_measured_from_it():
    elevation_rad = np.radians(45.0)
    assert scenarios.straight_line_altitude_m(1234.0, elevation_rad) == pytest.approx(1234.0)
    flight = _flight(45.0)
    flight["altitude_m"] = flight.ground_range_m - 7.0  # 7 m under the 45 deg line throughout
    assert np.allclose(scenarios.height_over_straight_line_m(flight), -7.0)


def test_drag_to_gravity_crossings_are_the_first_rows_below_each_ratio_on_the_way_up():
    flight = _flight()
    crossings = scenarios.drag_to_gravity_crossings(flight, (100.0, 1.0, 0.01))
    assert list(crossings.index) == [1.0, 0.01]  # N starts at 20: 100 is never crossed
    for ratio, row in crossings.iterrows():
        rising = flight[flight.time_s <= row.time_s]
        assert row.drag_to_gravity < ratio and (rising.drag_to_gravity.iloc[:-1] >= ratio).all()


def test_yaw_drag_peak_ignores_the_rise_near_impact():
    peak = scenarios.yaw_drag_peak(_flight())
    assert peak.time_s == 60.0 and peak.angle_of_attack_rad == pytest.approx(0.6)
