"""Chapter 3's drawing helpers: Fig 3.4's resonances drawn to the response's height."""

import numpy as np
import pytest

from harp_analysis.engines import nonlinear_kepler
from harp_analysis.reporting.figures import modified_kepler

COARSE = np.logspace(-1, 4, 600)  # Fig 3.4's frequencies before the resonances are added
TOP = 1e2


@pytest.mark.parametrize("omega_n", [1.0, 3.7, 17.1])
def test_resonance_grid_reaches_the_axis_top_at_the_resonance(omega_n):
    """|1/(omega_n^2 - omega^2)| = TOP at omega = sqrt(omega_n^2 -+ 1/TOP) (closed form); the
    grid holds both, so the drawn curve crosses the axis's top there and rises beyond it (the
    undamped response is unbounded at omega_n), whatever the spacing of the coarse grid."""
    grid = modified_kepler.resonance_grid(COARSE, omega_n, TOP)
    response = nonlinear_kepler.frequency_response(grid, omega_n)
    for crossing in (np.sqrt(omega_n**2 - 1 / TOP), np.sqrt(omega_n**2 + 1 / TOP)):
        (at,) = np.flatnonzero(np.isclose(grid, crossing, rtol=1e-14, atol=0))
        assert response[at] == pytest.approx(TOP, rel=1e-9)
    near = np.abs(grid - omega_n) < 0.5 * omega_n
    assert response[near].max() >= 1e6 * TOP * (1 - 1e-6)  # runs far off the top, not a stub
    assert np.all(np.diff(grid) > 0) and set(COARSE) <= set(grid)


def test_the_coarse_grid_alone_sets_the_peak_by_its_spacing():
    """What the grid repairs: on the coarse grid the peak's height is the nearest sample's,
    below the axis's top for omega_n = 17.1 (HP's at launch) and different for a near twin."""
    peaks = [nonlinear_kepler.frequency_response(COARSE, w).max() for w in (17.1, 17.2)]
    assert max(peaks) < TOP
    assert peaks[0] != pytest.approx(peaks[1], rel=0.1)
