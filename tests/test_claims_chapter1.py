"""The quantities of harp_analysis.analyses.claims.chapter1, checked against independent physics:
closed forms, numerical integration, limits and bounds."""

import math
import warnings

import pytest
from scipy.integrate import solve_ivp

from harp_analysis.analyses import effort, scenarios
from harp_analysis.analyses.claims import chapter1
from harp_analysis.analyses.comparisons import chapter_4_launch
from harp_analysis.engines import mks, threedof
from harp_analysis.foundation import earth
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models.launch import HP_CHAPTER_2, chapter_2
from harp_analysis.models.projectiles import BASELINE, LP

R, GM = earth.RADIUS_M, earth.GM_M3_S2


# --- Chapter 1 A-B: the V-3, Kepler and flat fire ---------------------------------------------
def test_tangent_line_ceiling_is_the_flat_tangent_plus_the_earths_drop():
    reach, phi = 43e3, math.radians(34.0)
    t, angle = math.tan(phi), reach / R
    ceiling = chapter1.tangent_line_ceiling_m(reach, phi)
    # R cos(phi)/cos(Theta + phi) - R in powers of Theta: the flat tangent s tan(phi), then the
    # sphere's drop below the tangent plane and the slant of the ray
    series = R * (angle * t + angle**2 * (0.5 + t**2) + angle**3 * (t**3 + 5 * t / 6))
    assert ceiling == pytest.approx(series, abs=0.05)
    assert ceiling == pytest.approx(reach * t, rel=0.01)


def test_no_trajectory_climbs_above_its_launch_tangent_line():
    """A heavily dragged flight (LP through the air at 34 deg) and the drag-free one."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        for atmosphere in ("two_segment", "vacuum"):
            launch = chapter_2(LP, elevation_deg=34.0, cross_wind_m_s=0.0, atmosphere=atmosphere)
            flight = threedof.simulate_3dof(launch)
            ceiling = chapter1.tangent_line_ceiling_m(flight.attrs["range_m"], math.radians(34))
            assert flight.attrs["apogee_altitude_m"] < ceiling


def test_v3_drag_free_apogee_is_a_quarter_of_range_times_tan_on_a_flat_earth():
    assert chapter1.v3_drag_free_apogee_km(43.0, 34.0) == pytest.approx(
        43.0 * math.tan(math.radians(34.0)) / 4, rel=0.005
    )


def _flat_fire_numerically(speed, phi, k, g):
    """The flat-fire equations du/dt = -k' u^2, dw/dt = -g - k' u w (k' = k sec(phi0))."""
    rate = k / math.cos(phi)

    def rhs(t, y):
        return [y[2], y[3], -rate * y[2] ** 2, -g - rate * y[2] * y[3]]

    land = lambda t, y: y[1] if t > 0 else 1.0  # noqa: E731
    land.terminal, land.direction = True, -1
    top = lambda t, y: y[3]  # noqa: E731
    state = [0.0, 0.0, speed * math.cos(phi), speed * math.sin(phi)]
    solution = solve_ivp(rhs, (0, 1e4), state, rtol=1e-11, atol=1e-9, events=(land, top))
    return solution.y_events[1][0][1], solution.y_events[0][0][0]


@pytest.mark.parametrize("k", [1e-9, 2.5e-5, 1e-4])
def test_flat_fire_closed_form_matches_its_differential_equations(k):
    speed, phi, g = 2022.0, math.radians(50.0), 9.8
    apogee, reach = chapter1.flat_fire_apogee_and_range_m(speed, phi, k, g)
    numeric_apogee, numeric_reach = _flat_fire_numerically(speed, phi, k, g)
    assert apogee == pytest.approx(numeric_apogee, rel=1e-6)
    assert reach == pytest.approx(numeric_reach, rel=1e-6)


def test_flat_fire_without_drag_is_the_vacuum_parabola():
    speed, phi, g = 700.0, math.radians(34.0), 9.81
    apogee, reach = chapter1.flat_fire_apogee_and_range_m(speed, phi, 1e-12, g)
    assert apogee == pytest.approx(speed**2 * math.sin(phi) ** 2 / (2 * g), rel=1e-6)
    assert reach == pytest.approx(speed**2 * math.sin(2 * phi) / g, rel=1e-6)


@pytest.mark.parametrize("projectile, elevation", [("HP", 50.0), ("LP", 50.0), ("baseline", 45.0)])
@pytest.mark.parametrize("measure", ["apogee", "range"])
def test_the_simulation_lies_between_vacuum_and_constant_sea_level_air(
    projectile, elevation, measure
):
    """Drag only lowers a flight, and the real air is never denser than at the gun."""
    assert chapter1.kepler_over_3dof(projectile, elevation, measure) > 1
    assert chapter1.flat_fire_over_3dof(projectile, elevation, measure) < 1


# --- Chapter 1 A-C: HARP's highest round, the engines' cost and accuracy, the air in orbit ----
def test_the_highest_harp_apogee_is_590000_feet():
    assert chapter1.max_measured_apogee_km("both") == pytest.approx(590_000 * 0.3048e-3, 1e-4)
    assert chapter1.max_measured_apogee_km("barbados") < chapter1.max_measured_apogee_km()


def test_mlt_operations_go_as_the_number_of_segments():
    one, two = (chapter1.mlt_over_3dof_orders(length) for length in (1000.0, 2000.0))
    assert one - two == pytest.approx(math.log10(2.0), abs=0.01)
    flops = effort.effort_table().flops  # the effort table's MLT flies 1 km segments
    assert one == pytest.approx(math.log10(flops["MLT"] / flops["3DOF"]), abs=1e-9)


def test_mks_apogee_miss_share_against_a_separate_6dof_run():
    six = scenarios.reference_6dof("HP", "spherical").attrs["apogee_altitude_m"]
    mks_apogee = float(mks.for_launch(HP_CHAPTER_2, warn=False).apogee_altitude())
    assert chapter1.mks_apogee_miss_share() == pytest.approx(abs(mks_apogee - six) / six, 1e-3)


def test_flat_fire_miss_is_the_gap_between_the_flat_fire_and_3dof_ranges():
    launch = chapter_4_launch("HP", 50.0).but(cross_wind_m_s=0.0, spin_rad_s=0.0)
    simulated = threedof.simulate_3dof(launch).attrs["range_m"]
    flat = chapter1.flat_fire_over_3dof("HP", 50.0, "range") * simulated
    assert chapter1.flat_fire_miss_km("HP", 50.0, "range") == pytest.approx(
        (simulated - flat) / 1e3, rel=1e-6
    )


def test_orbital_drag_uses_the_1976_density_at_200_km():
    # the printed 1976 table: 2.541e-10 kg/m^3 at 200 km (the ussa1976 package that
    # atmosphere.standard_density tabulates runs 3 % above it there, 0.15 % at 100 km)
    density, radius = 2.541e-10, R + 200e3
    speed_squared, gravity = GM / radius, GM / radius**2  # circular orbit
    drag = 0.5 * density * speed_squared * 2.2 * BASELINE.reference_area_m2 / BASELINE.mass_kg
    assert chapter1.orbital_drag_to_gravity(200.0) == pytest.approx(drag / gravity, rel=0.05)
    assert chapter1.orbital_drag_to_gravity(400.0) < chapter1.orbital_drag_to_gravity(200.0)
