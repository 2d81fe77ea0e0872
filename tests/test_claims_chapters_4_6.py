"""The Chapter 4-6 quantities added for the sweep's rows (harp_analysis.analyses.comparisons,
.rotating and .harp), checked against independent physics: conservation laws, closed forms, the
launch geometry of harp_analysis.engines.eci and textbook statistics."""

import math

import numpy as np
import pytest
from scipy import stats
from scipy.integrate import quad

from harp_analysis.analyses import comparisons, rotating
from harp_analysis.analyses.harp import apogees, appendices
from harp_analysis.analyses.harp import rounds as harp_rounds
from harp_analysis.engines import eci
from harp_analysis.foundation import earth
from harp_analysis.models.atmosphere import DRY_AIR_GAS_CONSTANT_J_KG_K
from harp_analysis.models.launch import baseline_chapter_4
from harp_analysis.models.projectiles import BASELINE

R, GM = earth.RADIUS_M, earth.GM_M3_S2


# --- comparisons: the angular momentum error split --------------------------------------------
@pytest.mark.parametrize("elevation_deg", comparisons.BASELINE_ELEVATIONS_DEG)
def test_decay_integral_reproduces_the_simulated_angular_momentum(elevation_deg):
    """d ln h / ds = -rho Cd A / (2 m) (drag along the velocity, gravity central): the integral
    along the 3DOF's path equals the 3DOF's own ln(h0 / h_apogee)."""
    parts = comparisons.momentum_decay_parts("baseline", elevation_deg)
    beta = comparisons.mks_beta("baseline", elevation_deg)
    assert parts["total"] + beta == pytest.approx(parts["simulated"], rel=1e-5)
    assert sum(parts[p] for p in comparisons.MOMENTUM_PARTS) == pytest.approx(parts["total"])


@pytest.mark.parametrize("elevation_deg", [30.0, 65.0])
def test_beta_is_the_straight_line_integral_through_exponential_air(elevation_deg):
    launch = baseline_chapter_4(elevation_deg)
    cd0, area, mass = launch.launch_drag_coefficient, BASELINE.reference_area_m2, BASELINE.mass_kg
    sine = math.sin(launch.elevation_rad)
    integral, _ = quad(
        lambda s: 1.225 * math.exp(-0.117e-3 * s * sine) * cd0 * area / (2 * mass), 0, np.inf
    )
    assert comparisons.mks_beta("baseline", elevation_deg) == pytest.approx(integral, rel=1e-9)


def test_gravity_bends_the_path_into_denser_air_than_the_straight_line():
    """The flight falls below its launch line, so it meets more air: the straight-line part is
    positive, and shrinks as the path straightens with elevation."""
    parts = [
        comparisons.momentum_decay_parts("baseline", e)["straight_line"]
        for e in comparisons.BASELINE_ELEVATIONS_DEG
    ]
    assert all(p > 0 for p in parts)
    assert comparisons.elevation_ordering_share("straight_line") == 1.0


def test_gravity_bending_leads_the_momentum_error_only_where_the_path_curves():
    """The straight-line part (gravity bending the path into denser air than the launch line
    meets) is the largest of the three at 30 deg, where the path curves most, and nearly
    vanishes at 85 deg (under 1e-4 of ln h), where it barely curves: so it leads at some
    elevations and not all. The longest path through the air, at 30 deg, has the largest
    error at apogee, so the error falls at least across the first step."""
    low = comparisons.momentum_decay_parts("baseline", 30.0)
    assert max(comparisons.MOMENTUM_PARTS, key=lambda name: abs(low[name])) == "straight_line"
    assert abs(comparisons.momentum_decay_parts("baseline", 85.0)["straight_line"]) < 1e-4
    assert 0.25 <= comparisons.largest_momentum_part_share("straight_line") <= 0.75
    assert comparisons.largest_momentum_part_share("air") < 1.0
    errors = [
        comparisons.error_at_apogee_km("baseline", e) for e in comparisons.BASELINE_ELEVATIONS_DEG
    ]
    assert errors[0] == max(errors)
    assert comparisons.elevation_ordering_share("trajectory_error") >= 1 / 3
    with pytest.raises(ValueError, match="part"):
        comparisons.momentum_error_share("wind")


# --- comparisons: errors, speed, wind ---------------------------------------------------------
@pytest.mark.parametrize("elevation_deg", [45.0, 85.0])
def test_at_apogee_the_error_is_the_hypotenuse_of_its_radial_and_along_track_parts(elevation_deg):
    """Law of cosines: an along-track step eps_t on a path climbing at Phi and a radial step
    eps_r add to eps_r^2 + eps_t^2 + 2 eps_r eps_t sin(Phi); near apogee Phi is small."""
    flight, _, errors = comparisons.case("baseline", elevation_deg)
    at = flight.attrs["apogee_time_s"]
    eps_r = np.interp(at, errors.time_s, errors.radial_error_m)
    phi = np.interp(at, errors.time_s, errors.phi_mks_rad)
    assert abs(phi) < 0.05
    total = comparisons.error_at_apogee_km("baseline", elevation_deg) * 1e3
    eps_t = comparisons.along_track_share_at_apogee("baseline", elevation_deg) * total
    cross = 2 * eps_r * np.interp(at, errors.time_s, errors.along_track_error_m) * np.sin(phi)
    assert eps_r**2 + eps_t**2 + cross == pytest.approx(total**2, rel=1e-3)


def test_mks_speed_conserves_the_asymptotic_conics_energy_above_the_air():
    """Above the atmosphere eq 4.2's speed obeys vis-viva: V^2/2 - GM/r is constant."""
    solution = comparisons.case("HP", 50.0)[1]
    theta = np.array([0.02, 0.03, 0.035])  # 130-220 km downrange: the drive has died out
    energy = solution.speed(theta) ** 2 / 2 - GM / solution.radius(theta)
    assert np.ptp(energy) < 1e-9 * abs(energy[0])
    assert comparisons.speed_divergence("HP", 50.0, "ascent") < 0.05


def test_speed_divergence_is_zero_at_the_gun():
    flight, solution, _ = comparisons.case("HP", 50.0)
    assert solution.speed(np.array([0.0]))[0] == pytest.approx(flight.speed_m_s.iloc[0])


def test_wind_moves_nothing_without_wind_and_less_than_the_wind_run_with_it():
    assert comparisons.wind_over_mks_error("baseline", 45.0) == 0.0
    flight = comparisons.case("HP", 50.0)[0]
    run = 5.0 * flight.attrs["apogee_time_s"]  # the air's own travel up to apogee
    shift = comparisons.wind_over_mks_error("HP", 50.0) * 1e3
    shift *= comparisons.error_at_apogee_km("HP", 50.0, cross_wind_m_s=0.0)
    assert 0.0 < shift < run


def test_table_beta_identity_against_the_mks_beta():
    """beta = N0 g / (k V0^2 sin phi0) for the MKS's own beta and drag/weight at the gun."""
    launch = comparisons.chapter_4_launch("LP", 50.0)
    p = launch.projectile
    n0 = 0.5 * 1.225 * launch.speed_m_s**2 * launch.launch_drag_coefficient
    n0 *= p.reference_area_m2 / (p.mass_kg * 9.81)
    assert comparisons.table_beta_from_drag_to_weight(n0, launch.speed_m_s, 50.0) == pytest.approx(
        comparisons.mks_beta("LP", 50.0), rel=1e-12
    )


# --- comparisons: the path, the printed error, air and Cd -------------------------------------
@pytest.mark.parametrize("elevation_deg", [30.0, 65.0])
def test_flight_path_turn_in_vacuum_is_the_conics(elevation_deg):
    """Energy and angular momentum give phi at height H: cos phi = R V0 cos phi0 / ((R+H) V)."""
    speed, height = 2157.0, 20e3
    turn = comparisons.flight_path_turn_deg(elevation_deg, 20.0, atmosphere="vacuum")
    v = math.sqrt(speed**2 - 2 * GM * (1 / R - 1 / (R + height)))
    phi = math.acos(R * speed * math.cos(math.radians(elevation_deg)) / ((R + height) * v))
    assert turn == pytest.approx(elevation_deg - math.degrees(phi), abs=1e-3)


def test_faster_flight_turns_about_as_the_inverse_square_of_speed():
    """dphi/dt = -g cos(phi)/V over a climb time ~ H/(V sin phi): the turn goes as 1/V^2."""
    ratio = comparisons.straighter_ratio("speed_plus_20pct")
    assert (2157.0 / 2590.0) ** 2 - 0.05 < ratio < 1.0


def test_printed_error_is_eq_4_7_as_printed():
    flight, solution, errors = comparisons.case("HP", 50.0)
    at = flight.attrs["apogee_time_s"]
    eps_r = np.interp(at, errors.time_s, errors.radial_error_m)
    eps_t = np.interp(at, errors.time_s, errors.along_track_error_m)
    phi = np.interp(at, errors.time_s, errors.phi_printed_rad)
    printed = math.hypot(eps_r + eps_t * math.cos(phi), eps_t * math.sin(phi))
    assert comparisons.error_at_apogee_printed_km("HP", 50.0) == pytest.approx(
        printed / 1e3, rel=1e-3
    )


def test_no_air_beats_vacuum_where_the_mks_is_kepler_s_exact_conic():
    """Without air the MKS's beta is 0 and it is the conic the 3DOF flies: vacuum improves on
    the three-layer air at every elevation, and the three-layer air on vacuum at none."""
    assert comparisons.error_at_apogee_km("baseline", 30.0, atmosphere="vacuum") < 1e-6
    assert comparisons.atmosphere_improved_share("vacuum", "three_layer") == 1.0
    assert comparisons.atmosphere_improved_share("three_layer", "vacuum") == 0.0


def test_cd_rise_follows_eq_4_8_and_the_falling_mach_number():
    """Eq 4.8 falls with Mach, and the Mach number falls on the way up in the isothermal layer."""
    rises = []
    for elevation in comparisons.BASELINE_ELEVATIONS_DEG:
        flight = comparisons.case("baseline", elevation)[0]
        ascent = flight[flight.time_s <= flight.attrs["apogee_time_s"]]
        mach = np.interp([20e3, 45e3], ascent.altitude_m, ascent.mach)
        assert mach[1] < mach[0]
        cd = 0.077 * np.exp(-0.38 * mach) + 0.014
        rises.append(cd[1] / cd[0] - 1)
    assert comparisons.cd_rise_between(20.0, 45.0) == pytest.approx(min(rises), rel=1e-3)


# --- rotating ---------------------------------------------------------------------------------
@pytest.mark.parametrize("bearing_deg", rotating.BEARINGS_DEG)
@pytest.mark.parametrize("latitude_deg", rotating.LATITUDES_DEG)
def test_air_profile_at_the_gun_is_the_launch_correction(latitude_deg, bearing_deg):
    """At t = 0 the law-of-cosines angle and speed ratio are eci's from the launch vectors."""
    elevation = 45.0
    profile = rotating.air_profile(latitude_deg, bearing_deg, elevation)
    relative = eci.relative_velocity(
        2157.0, math.radians(elevation), math.radians(bearing_deg), math.radians(latitude_deg)
    )
    inertial = relative + eci.surface_velocity(math.radians(latitude_deg))
    first = profile.iloc[0]
    assert first.air_speed_m_s == pytest.approx(2157.0, rel=1e-9)
    assert first.misalignment_rad == pytest.approx(
        float(eci.misalignment_angle(relative, inertial)), abs=1e-6
    )
    assert first.speed_ratio_squared == pytest.approx(
        float(eci.speed_ratio_squared(relative, inertial)), rel=1e-9
    )


def test_rotating_shares_and_ratios_are_consistent():
    assert rotating.west_over(90.0) == pytest.approx(rotating.west_over_east())
    assert rotating.lowest_elevation_worst_share() * 6 == pytest.approx(
        round(rotating.lowest_elevation_worst_share() * 6)
    )
    everything = rotating.largest_extent_under_km("apogee", max_error_km=1e9)
    assert everything >= rotating.largest_extent_under_km("apogee")
    with pytest.raises(ValueError, match="by"):
        rotating.west_ordering_share("bearing")


def test_speed_ratio_changes_as_a_constant_omega_r_against_a_falling_speed():
    """|Vrel|^2 = |V - w|^2 with w fixed: (Vrel/V)^2 = 1 - 2 V.w/V^2 + w^2/V^2 moves away from
    1 as V falls; the change below 20 km is largest at the lowest, slowest climb."""
    change = rotating.speed_ratio_change_below(20.0)
    profile = rotating.air_profile(0.0, 270.0, 30.0)
    low = profile[profile.altitude_m <= 20e3].speed_ratio_squared
    assert change == pytest.approx(np.max(np.abs(low / low.iloc[0] - 1)))
    assert profile.speed_ratio_squared.iloc[0] > 1.0  # west: the air meets it faster


# --- harp -------------------------------------------------------------------------------------
def test_round_counts_match_the_transcription():
    table = appendices.load_barbados()
    assert apogees.round_count("barbados", distinct=False) == len(table)
    assert apogees.round_count("barbados") == table.round_number.nunique()
    assert apogees.round_count("yuma") == 22


def _welch(quantity: str = "residual"):
    """Barbados' and Yuma's distinct rounds (residuals or muzzle speeds), each mean's variance
    and the Welch-Satterthwaite degrees of freedom, by hand."""
    samples = []
    for site in ("barbados", "yuma"):
        if quantity == "residual":
            frame = apogees.predicted_apogees(site)
            samples.append(frame.residual_m[~frame.duplicate_of_earlier_row].to_numpy())
        else:
            rounds = apogees.appendix_rounds(site)
            samples.append(rounds.muzzle_speed_m_s[~rounds.duplicate_of_earlier_row].to_numpy())
    a, b = samples
    va, vb = a.var(ddof=1) / a.size, b.var(ddof=1) / b.size
    dof = (va + vb) ** 2 / (va**2 / (a.size - 1) + vb**2 / (b.size - 1))
    return a, b, va, vb, dof


@pytest.mark.parametrize("quantity", ["residual", "muzzle_speed"])
def test_site_difference_p_value_is_welchs(quantity):
    """Welch's t and the Welch-Satterthwaite degrees of freedom, by hand."""
    a, b, va, vb, dof = _welch(quantity)
    t = (a.mean() - b.mean()) / math.sqrt(va + vb)
    assert apogees.site_difference_p_value(quantity) == pytest.approx(
        2 * stats.t.sf(abs(t), dof), rel=1e-9
    )


@pytest.mark.parametrize("margin_m", [300.0, 1000.0, 5000.0])
def test_site_equivalence_is_the_two_one_sided_welch_tests(margin_m):
    """TOST by hand: Welch's t against a difference of -margin and of +margin, each one-sided;
    the larger p. A wide margin shows equivalence, a narrow one cannot."""
    a, b, va, vb, dof = _welch()
    difference, se = a.mean() - b.mean(), math.sqrt(va + vb)
    p_above = stats.t.sf((difference + margin_m) / se, dof)
    p_below = stats.t.cdf((difference - margin_m) / se, dof)
    p = apogees.site_equivalence_p_value("residual", margin=margin_m)
    assert p == pytest.approx(max(p_above, p_below), rel=1e-9)
    assert (p < 0.05) is (margin_m == 5000.0)


@pytest.mark.parametrize("margin_m", [300.0, 1000.0, 2600.0, 5000.0])
def test_site_mean_difference_is_welchs_interval_and_tost_s(margin_m):
    """Issue 34: the sites' difference with its 90 % Welch interval, by hand (Welch-Satterthwaite
    degrees of freedom, Student's t quantile), and the interval's duality with the two one-sided
    tests: inside +-margin exactly when TOST shows equivalence at 5 %."""
    a, b, va, vb, dof = _welch()
    half = stats.t.ppf(0.95, dof) * math.sqrt(va + vb)
    found = apogees.site_mean_difference("residual")
    assert found.estimate == pytest.approx(b.mean() - a.mean(), rel=1e-12)
    assert (found.low, found.high) == pytest.approx(
        (b.mean() - a.mean() - half, b.mean() - a.mean() + half), rel=1e-9
    )
    shown = max(abs(found.low), abs(found.high)) <= margin_m
    assert shown is (apogees.site_equivalence_p_value("residual", margin=margin_m) < 0.05)
    relative = apogees.site_mean_difference("residual", relative=True)
    share = abs(np.concatenate([a, b]).mean())
    assert relative.high == pytest.approx(found.high / share, rel=1e-12)


def test_bearings_temperatures_and_splash():
    assert apogees.bearing_from_east_deg("barbados") == pytest.approx(19.0)
    assert apogees.bearing_from_east_deg() == pytest.approx(19.0)
    a_yuma, a_barbados = apogees.speed_of_sound("yuma")[0], apogees.speed_of_sound("barbados")[0]
    assert apogees.mach_column_temperature_difference_k() == pytest.approx(
        (a_yuma**2 - a_barbados**2) / (1.4 * DRY_AIR_GAS_CONSTANT_J_KG_K)
    )
    assert harp_rounds.splash_error() == pytest.approx(41.1 - harp_rounds.splash_range_km())
    assert harp_rounds.splash_error(relative=True) == pytest.approx(
        harp_rounds.splash_error() / 41.1
    )
