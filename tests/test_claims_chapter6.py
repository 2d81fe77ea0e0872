"""The quantities of harp_analysis.analyses.claims.chapter6, checked against the standard
atmosphere, the appendices' speed of sound and eq 6.1's terms."""

import math

import numpy as np
import pytest

from harp_analysis.analyses.claims import chapter6
from harp_analysis.analyses.harp import apogees


def test_density_at_the_standard_sea_level_temperature_is_the_standards():
    assert chapter6.density_at_temperature_kg_m3(288.15) == pytest.approx(1.2250, abs=5e-5)
    assert chapter6.fahrenheit_to_kelvin(32.0) == pytest.approx(273.15)
    assert chapter6.fahrenheit_to_kelvin(212.0) == pytest.approx(373.15)


def test_site_density_from_the_mach_column_uses_its_speed_of_sound():
    a = apogees.speed_of_sound("barbados")[0]
    temperature = a**2 / (1.4 * 287.05)
    expected = 101325.0 / (287.05287 * temperature)
    assert chapter6.site_density_kg_m3("barbados") == pytest.approx(expected, rel=1e-4)


def test_eq_6_4_apogee_is_the_true_zero_of_eq_6_1():
    for site in ("barbados", "yuma"):
        solution = chapter6.harp_solution(site)
        theta = np.atleast_1d(solution.apogee_angle_eq_6_4)
        # tau theta at apogee is large, so the dropped terms are below e^-20 of the kept ones
        assert np.all(solution.tau[:, 0] * theta > 20)
        assert chapter6.apogee_drive_ratio(site) < math.exp(-20)
        assert chapter6.apogee_simplification_shift_km(site) < 1e-6


def test_min_measured_apogee():
    table = apogees.appendix_rounds("yuma")
    assert chapter6.min_measured_apogee_km("yuma") == pytest.approx(table.apogee_m.min() / 1e3)
