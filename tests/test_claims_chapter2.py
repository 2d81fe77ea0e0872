"""The quantities of harp_analysis.analyses.claims.chapter2, checked against independent physics:
closed forms, error laws, conservation laws and first-order expansions."""

import math

import numpy as np
import pytest
from scipy import constants

from harp_analysis.analyses import comparisons
from harp_analysis.analyses.claims import chapter2
from harp_analysis.foundation import earth
from harp_analysis.models import atmosphere
from harp_analysis.models.projectiles import HP, LP

R, GM = earth.RADIUS_M, earth.GM_M3_S2


def _stormer_final_x(dt, correct_start):
    """x at t = 10 of the oscillator x'' = -x (x = 1, x' = 1 at 0) flown by Appendix A's
    recurrence x2 = 2 x1 - x0 + a dt^2, started as the listing does (x1 = x0 + v0 dt) or with
    the a dt^2/2 term. (The Earth's gravity is too uniform over a flight for the recurrence's
    own second-order error to stand out of the round-off.)"""
    x0, v0 = 1.0, 1.0
    x1 = x0 + v0 * dt - (0.5 * x0 * dt**2 if correct_start else 0.0)
    for _ in range(round(10.0 / dt) - 1):
        x0, x1 = x1, 2 * x1 - x0 - x1 * dt**2
    return x1


@pytest.mark.parametrize("correct_start, order", [(True, 2.0), (False, 1.0)])
def test_observed_order_of_the_stormer_recurrence(correct_start, order):
    finals = [_stormer_final_x(dt, correct_start) for dt in (0.05, 0.025, 0.0125)]
    assert chapter2.observed_order(*finals) == pytest.approx(order, abs=0.06)


def test_observed_order_of_known_error_laws():
    for p in (1.0, 2.0, 4.0):
        assert chapter2.observed_order(*(3.0 + 0.7 * h**p for h in (0.2, 0.1, 0.05))) == (
            pytest.approx(p, abs=1e-9)
        )
    assert math.isnan(chapter2.observed_order(1.0, 2.0, 1.0))  # not converging


def test_similar_inertia_is_a_scaled_cylinders():
    def cylinder(mass, radius, length):  # pitch inertia of a solid cylinder about its centre
        return mass * (3 * radius**2 + length**2) / 12

    scale = (HP.mass_kg / LP.mass_kg) ** (1 / 3)
    radius, length, density = 0.0134, 0.75, 7800.0
    small = density * math.pi * radius**2 * length
    ratio = cylinder(small * scale**3, radius * scale, length * scale) / cylinder(
        small, radius, length
    )
    assert chapter2.similar_inertia_kg_m2("pitch") / LP.pitch_inertia_kg_m2 == pytest.approx(
        ratio, rel=1e-12
    )


def test_lp_angle_of_attack_in_the_air_is_the_cross_wind_angle_at_the_muzzle():
    expected = math.degrees(math.atan2(5.0, 2022.0))
    assert chapter2.max_angle_of_attack_below_deg("LP", 30.0) == pytest.approx(expected, abs=1e-3)


def test_mach_over_speed_ratio_is_the_speeds_of_sound_ratio():
    sound = atmosphere.two_segment_speed_of_sound(np.array([0.0, 20e3]))
    assert chapter2.mach_over_speed_ratio_max("HP") == pytest.approx(sound[0] / sound[1], rel=2e-3)


def test_turn_in_a_vacuum_follows_from_energy_and_angular_momentum():
    speed, phi, top = HP.launch_speed_m_s, math.radians(50.0), 20e3
    radius = R + top
    speed_at = math.sqrt(speed**2 - 2 * GM * (1 / R - 1 / radius))
    angle = math.acos(R * speed * math.cos(phi) / (radius * speed_at))
    turn = chapter2.ascent_change_below("HP", "turn", 20.0, atmosphere="vacuum")
    assert turn == pytest.approx(math.degrees(phi - angle), abs=1e-3)
    assert chapter2.ascent_change_below("HP", "speed", 20.0, atmosphere="vacuum") == (
        pytest.approx(1 - speed_at / speed, abs=1e-6)
    )


def test_gravity_dominant_share_grows_with_the_ratio():
    shares = [chapter2.gravity_dominant_share("HP", n) for n in (0.1, 1.0, 1e9)]
    assert shares[0] < shares[1] < shares[2] == pytest.approx(1.0, abs=1e-12)


def test_text_gm_with_the_codata_constant():
    assert constants.G == pytest.approx(6.67430e-11, rel=1e-12)
    assert chapter2.text_gm_over_appendix_gm() == pytest.approx(
        6.67430e-11 * 5.972e24 / 398600.4418e9, rel=1e-12
    )


def test_break_jump_from_the_printed_equations():
    below = 1.22581 * (1 - 0.00002257 * 10769.0) ** 4.256  # eq 2.2
    above = 0.37454745  # eq 2.1 at its start
    assert chapter2.two_segment_break_jump() == pytest.approx(above / below - 1, abs=2e-6)


@pytest.mark.parametrize("projectile", ["HP", "LP"])
def test_ascent_momentum_loss_near_the_straight_line_decay(projectile):
    # eq 3.23: h_inf = h0 exp(-beta) for a straight climb through eq 3.11's air
    beta = comparisons.mks_beta(projectile, 50.0)
    assert chapter2.momentum_loss(projectile, "ascent") == pytest.approx(
        1 - math.exp(-beta), abs=0.03
    )
    assert 0 < chapter2.momentum_loss(projectile, "reentry") < 1


def test_rotation_shift_of_a_short_vacuum_shot_is_the_first_order_one():
    # east, north, up at 45 deg N; fired north at 45 deg elevation, 200 m/s
    latitude, speed, omega = math.radians(45.0), 200.0, earth.ROTATION_RATE_RAD_S
    g = GM / R**2
    spin = omega * np.array([0.0, math.cos(latitude), math.sin(latitude)])
    velocity = speed * np.array([0.0, math.cos(math.pi / 4), math.sin(math.pi / 4)])
    t = 2 * velocity[2] / g
    # r'' = g - 2 Omega x v - Omega x (Omega x r), to first order about the vacuum parabola
    shift = (
        -np.cross(spin, velocity) * t**2
        - np.cross(spin, [0.0, 0.0, -g]) * t**3 / 3
        + 0.5 * omega**2 * R * math.cos(latitude) * np.array([0.0, -math.sin(latitude), 0.0]) * t**2
        + 0.5 * omega**2 * R * math.cos(latitude) ** 2 * np.array([0.0, 0.0, 1.0]) * t**2
    )
    on_ground = shift[:2] + velocity[:2] * shift[2] / velocity[2]  # later landing, further on
    computed = chapter2.rotation_impact_shift_km(speed, 45.0, 45.0, 0.0, atmosphere="vacuum")
    assert computed * 1e3 == pytest.approx(np.linalg.norm(on_ground), rel=0.02)


def test_only_a_rotating_earth_tells_launch_sites_apart():
    assert chapter2.nonrotating_spread_m(45.0) < 1e-2
    assert chapter2.nonrotating_spread_m(45.0, earth.ROTATION_RATE_RAD_S) > 1e3
