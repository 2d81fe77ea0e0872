"""The operation counter follows its stated rule, and the counted MKS code is the MKS."""

import numpy as np
import pytest

from harp_analysis import effort, mks
from harp_analysis.projectiles import BASELINE, HP


def _sample(x, y):
    """Two multiplies, two adds, a square (1), a sqrt (1) and an exp (10): 16."""
    return np.exp(x * y + x * x) + np.sqrt(y ** 2)


def test_counting_rule():
    assert effort.count_flops(_sample) == 2 + 2 + 1 + 1 + 10


def test_dop853_overhead_grows_with_states():
    assert effort.dop853_step_flops(12) - effort.dop853_step_flops(6) == 6 * (132 + 24 + 52 + 4)


@pytest.mark.parametrize("projectile, elevation", [(BASELINE, 45.0), (BASELINE, 85.0), (HP, 50.0)])
def test_counted_mks_apogee_is_the_mks(projectile, elevation):
    solution = mks.for_projectile(projectile, elevation, warn=False)
    cd0 = solution.beta.item() * 2 * 1.17e-4 * projectile.mass_kg * np.sin(
        np.radians(elevation)) / (1.225 * projectile.reference_area_m2)
    apogee = effort.mks_apogee(projectile.launch_speed_m_s, np.radians(elevation), cd0,
                               projectile.mass_kg, projectile.reference_area_m2)
    assert apogee == pytest.approx(solution.apogee_altitude("eq_6_4"), rel=1e-9)
