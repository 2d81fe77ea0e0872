"""The quantities of harp_analysis.analyses.claims.chapter3, checked against independent physics:
the vacuum, eq 3.27, the straight-line decay and eq 3.30 integrated numerically."""

import math

import pytest
from scipy.integrate import solve_ivp

from harp_analysis.analyses import comparisons
from harp_analysis.analyses.claims import chapter3
from harp_analysis.analyses.comparisons import chapter_4_launch
from harp_analysis.engines import mks
from harp_analysis.foundation import earth
from harp_analysis.models import atmosphere

R = earth.RADIUS_M


def test_kepler_handoff_is_exact_in_a_vacuum():
    for measure in ("path", "radial", "apogee"):
        error = chapter3.kepler_handoff_error_km("HP", 50.0, 30.0, measure, "vacuum")
        assert abs(error) < 1e-6  # km


def test_kepler_handoff_error_shrinks_with_altitude_and_path_is_under_radial():
    errors = [chapter3.kepler_handoff_error_km("HP", 50.0, a) for a in (20, 30, 40, 60)]
    assert all(a > b for a, b in zip(errors, errors[1:]))
    assert chapter3.kepler_handoff_error_km("HP", 50.0, 30.0) < (
        chapter3.kepler_handoff_error_km("HP", 50.0, 30.0, "radial")
    )
    with pytest.raises(ValueError, match="apogee"):
        chapter3.kepler_handoff_error_km("HP", 50.0, 100.0)


def test_natural_over_driving_frequency_is_one_over_eq_3_27():
    tau = 0.117e-3 * R * math.tan(math.radians(50.0))
    assert chapter3.natural_over_driving_frequency("HP", 50.0) == pytest.approx(1 / tau)


def test_baseline_momentum_share_near_the_straight_line_decay():
    beta = comparisons.mks_beta("baseline", 30.0)
    gamma = math.exp(-atmosphere.TEXT_DECAY_CONSTANT_PER_M * 20e3)
    straight = (1 - math.exp(beta * (gamma - 1))) / (1 - math.exp(-beta))
    share = chapter3.baseline_momentum_loss_share_below(20.0, elevations_deg=(30.0,))
    assert share == pytest.approx(straight, abs=0.03)


def test_converged_series_apogee_solves_eq_3_30_with_the_double_exponential():
    solution = mks.for_launch(chapter_4_launch("LP", 50.0), n_terms=15, warn=False)
    c3, beta, tau = (float(x[0, 0]) for x in (solution.c3, solution.beta, solution.tau))
    r0, phi = R, math.radians(50.0)

    def rhs(theta, y):  # eq 3.30 with the series summed: c3 exp(-2 beta e^{-tau theta})
        return [y[1], c3 * math.exp(-2 * beta * math.exp(-tau * theta)) - y[0]]

    top = lambda theta, y: y[1]  # noqa: E731
    top.terminal, top.direction = True, 1
    ode = solve_ivp(
        rhs,
        (0, 1.0),
        [1 / r0, -math.tan(phi) / r0],
        rtol=1e-12,
        atol=1e-20,
        events=top,
        first_step=1e-7,
        max_step=1e-3,
    )
    apogee = 1 / ode.y_events[0][0][0] - r0
    assert float(solution.apogee_altitude()) == pytest.approx(apogee, abs=0.1)
    needed = chapter3.series_terms_needed("LP", 50.0, 1.0)
    fewer = mks.for_launch(chapter_4_launch("LP", 50.0), n_terms=needed - 1, warn=False)
    assert abs(float(fewer.apogee_altitude()) - apogee) > 1.0
