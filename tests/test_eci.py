"""The rotating-Earth corrections of Chapter 5 against geometry, the non-rotating MKS, and the
derived columns printed in Appendices D (Barbados) and E (Yuma)."""

import math

import numpy as np
import pytest

from harp_analysis import earth, eci, mks
from harp_analysis.harp_data import load_appendix
from harp_analysis.projectiles import BASELINE
from harp_analysis.sites import BARBADOS, get_site

DEG = math.pi / 180


def test_barbados_surface_speed_eq_6_16():
    speed = np.linalg.norm(eci.surface_velocity(BARBADOS.latitude_rad))
    assert speed / 1e3 == pytest.approx(0.4518, abs=5e-5)


def _launch(speed, elevation_deg, bearing_deg, latitude_deg, **kwargs):
    return eci.launch_correction(speed, elevation_deg * DEG, bearing_deg * DEG,
                                 latitude_deg * DEG, drag_area_m2=2.7e-3, mass_kg=84.0,
                                 surface_density_kg_m3=1.225, **kwargs)


def test_due_east_at_the_equator_stays_in_the_vertical_plane():
    elevation = np.array([30.0, 60.0, 85.0])
    for include_tangent in (True, False):
        launch = _launch(1800.0, elevation, 90.0, 0.0, include_tangent=include_tangent)
        assert launch.azimuth_rad == pytest.approx(90 * DEG, abs=1e-12)
        assert np.all(launch.elevation_rad < elevation * DEG)   # V leans east, lower
    # Vrel, omega x r0 and V share the east-up plane: mu is the drop in elevation
    assert launch.misalignment_rad == pytest.approx(elevation * DEG - launch.elevation_rad,
                                                    abs=1e-12)


def test_due_north_at_the_equator_turns_east():
    launch = _launch(1800.0, 45.0, 0.0, 0.0, include_tangent=False)
    expected = math.atan2(earth.ROTATION_RATE_RAD_S * earth.RADIUS_M, 1800 * math.cos(45 * DEG))
    assert launch.azimuth_rad == pytest.approx(expected, rel=1e-12)
    # V_tangent (on the side away from Vrel) turns it further east
    assert expected < _launch(1800.0, 45.0, 0.0, 0.0).azimuth_rad < 90 * DEG


def test_misalignment_vanishes_as_the_speed_grows():
    mu = _launch(np.geomspace(1e3, 1e7, 9), 85.0, 109.0, 13.0).misalignment_rad
    assert np.all(np.diff(mu) < 0)
    assert mu[-1] < 1e-4


def test_tangent_velocity_lies_along_the_cross_track_drag():
    """V_tangent is normal to V, in the plane of Vrel and V, on the side of the drag -Vrel."""
    launch = _launch(1800.0, 85.0, 109.0, 13.0)
    corrected = launch.relative_m_s + launch.surface_m_s
    direction = eci.tangent_direction(launch.relative_m_s, corrected)
    assert np.linalg.norm(direction) == pytest.approx(1.0)
    assert direction @ corrected == pytest.approx(0.0, abs=1e-9)
    assert np.linalg.det(np.stack([direction, corrected, launch.relative_m_s])) == \
        pytest.approx(0.0, abs=1e-6)
    assert direction @ -launch.relative_m_s > 0
    # so adding it turns V further from Vrel: lower and more eastward for this shot
    with_tangent = _launch(1800.0, 85.0, 109.0, 13.0, include_tangent=True)
    without = _launch(1800.0, 85.0, 109.0, 13.0, include_tangent=False)
    assert with_tangent.elevation_rad < without.elevation_rad
    assert with_tangent.azimuth_rad < without.azimuth_rad


def test_speed_ratio_eq_5_3_is_exact_with_the_inertial_east_component():
    rng = np.random.default_rng(1)
    speed, elevation = rng.uniform(500, 3000, 50), rng.uniform(5, 89, 50) * DEG
    bearing, latitude = rng.uniform(0, 360, 50) * DEG, rng.uniform(-80, 80, 50) * DEG
    relative = eci.relative_velocity(speed, elevation, bearing, latitude)
    inertial = relative + eci.surface_velocity(latitude)
    exact = eci.speed_ratio_squared(relative, inertial)
    assert eci.speed_ratio_squared_eq_5_3(inertial, latitude) == pytest.approx(exact, rel=1e-12)
    assert exact == pytest.approx(speed**2 / np.sum(inertial**2, axis=0), rel=1e-12)


def test_eci_solution_without_rotation_is_the_non_rotating_mks():
    reference = mks.for_projectile(BASELINE, 45.0)
    cd0 = BASELINE.drag_law(2157.0 / mks.get_atmosphere("two_segment").speed_of_sound(0.0))
    solution = eci.eci_solution(2157.0, 45 * DEG, 1.0, 0.7,
                                drag_area_m2=cd0 * BASELINE.reference_area_m2,
                                mass_kg=BASELINE.mass_kg, surface_density_kg_m3=1.225,
                                rotation_rate_rad_s=0.0)
    for name in ("h_inf", "c1", "c2", "amplitudes", "beta", "tau"):
        assert getattr(solution, name) == pytest.approx(getattr(reference, name), rel=1e-9), name
    assert solution.apogee_altitude() == pytest.approx(reference.apogee_altitude(), rel=1e-9)


def test_eci_solution_scales():
    launch = _launch(1800.0, 85.0, 109.0, 13.0)
    solution = eci.eci_solution(1800.0, 85 * DEG, 109 * DEG, 13 * DEG, drag_area_m2=2.7e-3,
                                mass_kg=84.0, surface_density_kg_m3=1.225)
    cos_mu = math.cos(launch.misalignment_rad)
    assert solution.drive_scale[0, 0] == pytest.approx(cos_mu * launch.speed_ratio_squared)
    assert solution.decay_scale[0, 0] == pytest.approx(cos_mu)
    assert solution.h_inf[0, 0] == pytest.approx(launch.asymptotic_angular_momentum_m2_s)


# --- Appendices D and E ------------------------------------------------------------------------
# column: (printed unit per SI unit, printed half-unit)
COLUMNS = {"mach": (1.0, 0.005), "misalignment_angle_rad": (1 / DEG, 0.005),
           "tangent_speed_m_s": (1e-3, 0.005), "corrected_elevation_rad": (1 / DEG, 0.005),
           "corrected_speed_m_s": (1e-3, 0.005), "corrected_azimuth_rad": (1 / DEG, 0.005),
           "beta": (1.0, 0.005), "initial_angular_momentum_m2_s": (1e-6, 0.005)}
# Measured largest |computed - printed| (printed units) and whether printed precision plus the
# effect of rounding Vo to 0.01 km/s explains it.
MEASURED = {
    ("barbados", "mach"): (0.010, True), ("yuma", "mach"): (0.015, True),
    ("barbados", "misalignment_angle_rad"): (0.030, True),
    ("yuma", "misalignment_angle_rad"): (0.028, True),
    # eq 5.8 with the Cd0 A of the Beta column gives 7-15 % less than the printed V tangent
    ("barbados", "tangent_speed_m_s"): (0.012, False),
    ("yuma", "tangent_speed_m_s"): (0.012, False),
    ("barbados", "corrected_elevation_rad"): (0.020, True),
    ("yuma", "corrected_elevation_rad"): (0.027, True),
    ("barbados", "corrected_speed_m_s"): (0.009, True),
    ("yuma", "corrected_speed_m_s"): (0.007, True),
    # a systematic offset: computed azimuths are 0.22-0.25 deg (Barbados), 0.06-0.08 deg (Yuma) low
    ("barbados", "corrected_azimuth_rad"): (0.25, False),
    ("yuma", "corrected_azimuth_rad"): (0.082, False),
    # round 213 comes out 0.1949 (printed 0.20); Yuma's printed 0.16 needs a 3 % smaller Cd0 A
    ("barbados", "beta"): (0.0052, False), ("yuma", "beta"): (0.007, False),
    # Barbados L0 is 3.2-5.3 km^2/s (0.1 %) above the printed Li for every round
    ("barbados", "initial_angular_momentum_m2_s"): (5.4, False),
    ("yuma", "initial_angular_momentum_m2_s"): (2.6, True),
}


@pytest.fixture(scope="module")
def comparisons():
    result = {}
    for site in ("barbados", "yuma"):
        launch_site = get_site(site)
        printed = load_appendix(site)
        printed = printed[~printed["duplicate_of_earlier_row"]].reset_index(drop=True)
        computed = eci.appendix_columns(site)
        drag_area, sound = eci.fit_drag_area_m2(), eci.fit_speed_of_sound_m_s(site)

        def columns(offset):
            speed = printed["muzzle_speed_m_s"].to_numpy() + offset
            launch = eci.launch_correction(
                speed, launch_site.elevation_rad, launch_site.gun_bearing_rad,
                launch_site.latitude_rad, drag_area_m2=drag_area,
                mass_kg=printed["mass_kg"].to_numpy(),
                surface_density_kg_m3=launch_site.surface_density_kg_m3, include_tangent=False)
            return {"mach": speed / sound, "misalignment_angle_rad": launch.misalignment_rad,
                    "tangent_speed_m_s": launch.tangent_speed_m_s,
                    "corrected_elevation_rad": launch.elevation_rad,
                    "corrected_speed_m_s": launch.speed_m_s,
                    "corrected_azimuth_rad": launch.azimuth_rad, "beta": launch.beta,
                    "initial_angular_momentum_m2_s": launch.initial_angular_momentum_m2_s}
        low, high = columns(-5.0), columns(5.0)
        assert list(computed["round_number"]) == list(printed["round_number"])
        for column, (scale, half_unit) in COLUMNS.items():
            difference = (computed[column] - printed[column]).to_numpy() * scale
            rounding = half_unit + np.max(np.abs(high[column] - low[column])) / 2 * scale
            worst = int(np.argmax(np.abs(difference)))
            result[site, column] = (np.abs(difference[worst]),
                                    int(printed["round_number"][worst]), rounding)
    return result


@pytest.mark.parametrize("site, column", sorted(MEASURED))
def test_appendix_column_agreement(comparisons, site, column):
    worst, round_number, rounding = comparisons[site, column]
    bound, explained = MEASURED[site, column]
    assert worst <= bound, (f"{site} {column}: largest difference {worst:.4g} (round "
                            f"{round_number}) exceeds the measured {bound:g}")
    assert (worst <= rounding) == explained, (
        f"{site} {column}: largest difference {worst:.4g} (round {round_number}) against the "
        f"rounding tolerance {rounding:.4g}; expected explained={explained}")


def test_li_is_l0_not_l_inf():
    computed = eci.appendix_columns("barbados")
    printed = load_appendix("barbados").drop_duplicates("round_number").reset_index(drop=True)
    ratio = computed["initial_angular_momentum_m2_s"] / printed["initial_angular_momentum_m2_s"]
    assert np.all(np.abs(ratio - 1) < 2e-3)   # L_inf would be about 0.84 L0


@pytest.mark.parametrize("site", ["barbados", "yuma"])
def test_fitted_speed_of_sound_is_physical_and_central(site):
    """Vo/Mach of the printed rows brackets the fit, which is an air temperature of 280-310 K."""
    table = load_appendix(site)
    per_round = table["muzzle_speed_m_s"] / table["mach"]
    fitted = eci.fit_speed_of_sound_m_s(site)
    assert per_round.min() <= fitted <= per_round.max()
    assert np.sqrt(1.4 * 287.05 * 280) < fitted < np.sqrt(1.4 * 287.05 * 310)


def test_fitted_drag_area_minimises_the_beta_misfit():
    """The least-squares Cd0 A: moving it 1 % either way worsens the fit to the printed betas."""
    printed = load_appendix("barbados").drop_duplicates("round_number")["beta"].to_numpy()

    def misfit(drag_area):
        computed = eci.appendix_columns("barbados", drag_area_m2=drag_area)["beta"].to_numpy()
        return np.sum((computed - printed) ** 2)

    best = eci.fit_drag_area_m2()
    assert misfit(best) < misfit(0.99 * best) and misfit(best) < misfit(1.01 * best)


@pytest.mark.parametrize("call, name", [
    (lambda: eci.appendix_columns("mars"), "site"),
    (lambda: eci.relative_velocity(1800.0, 1.4, 2 * math.pi, 0.2), "bearing_rad"),
    (lambda: eci.relative_velocity(1800.0, 1.4, 1.0, 91 * DEG), "latitude_rad"),
    (lambda: eci.surface_velocity(91 * DEG), "latitude_rad"),
    (lambda: _launch(float("nan"), 85.0, 109.0, 13.0), "speed_m_s"),
    (lambda: eci.launch_correction(1800.0, 1.4, 1.0, 0.2, drag_area_m2=-1.0, mass_kg=84.0,
                                   surface_density_kg_m3=1.2), "drag_area_m2"),
])
def test_bad_input_is_named(call, name):
    with pytest.raises(ValueError, match=name):
        call()
