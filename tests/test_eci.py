"""The rotating-Earth corrections of Chapter 5 against geometry and the non-rotating MKS
(the appendices' columns are tested in test_harp.py)."""

import math
from dataclasses import replace

import numpy as np
import pytest

from harp_analysis.engines import eci, mks
from harp_analysis.foundation import earth
from harp_analysis.foundation.validation import Bounds, ModelValidityWarning
from harp_analysis.models.atmosphere import get_atmosphere
from harp_analysis.models.launch import HP_CHAPTER_2, Launches, baseline_chapter_4
from harp_analysis.models.projectiles import BASELINE
from harp_analysis.models.sites import BARBADOS

DEG = math.pi / 180
NO_TANGENT = replace(eci.CONSISTENT, name="no V_tangent", include_tangent=False)


def test_barbados_surface_speed_eq_6_16():
    speed = np.linalg.norm(eci.surface_velocity(BARBADOS.latitude_rad))
    assert speed / 1e3 == pytest.approx(0.4518, abs=5e-5)


def _launch(speed, elevation_deg, bearing_deg, latitude_deg, **kwargs):
    return eci.correction_for_arrays(
        speed,
        elevation_deg * DEG,
        bearing_deg * DEG,
        latitude_deg * DEG,
        drag_area_m2=2.7e-3,
        mass_kg=84.0,
        surface_density_kg_m3=1.225,
        **kwargs,
    )


def test_due_east_at_the_equator_stays_in_the_vertical_plane():
    elevation = np.array([30.0, 60.0, 85.0])
    for model in (eci.CONSISTENT, NO_TANGENT):
        launch = _launch(1800.0, elevation, 90.0, 0.0, model=model)
        assert launch.azimuth_rad == pytest.approx(90 * DEG, abs=1e-12)
        assert np.all(launch.elevation_rad < elevation * DEG)  # V leans east, lower
    # Vrel, omega x r0 and V share the east-up plane: mu is the drop in elevation
    assert launch.misalignment_rad == pytest.approx(
        elevation * DEG - launch.elevation_rad, abs=1e-12
    )


def test_due_north_at_the_equator_turns_east():
    launch = _launch(1800.0, 45.0, 0.0, 0.0, model=NO_TANGENT)
    expected = math.atan2(earth.ROTATION_RATE_RAD_S * earth.RADIUS_M, 1800 * math.cos(45 * DEG))
    assert launch.azimuth_rad == pytest.approx(expected, rel=1e-12)
    # V_tangent (on the side away from Vrel) turns it further east
    assert expected < _launch(1800.0, 45.0, 0.0, 0.0).azimuth_rad < 90 * DEG


def test_misalignment_vanishes_as_the_speed_grows():
    """mu is the angle between Vrel and Vrel + omega x r0: adding a vector of length s to one
    of length V turns it by at most asin(s / V), so mu falls at least as fast as 1 / V."""
    speeds = np.geomspace(1e3, 1e7, 9)
    mu = _launch(speeds, 85.0, 109.0, 13.0).misalignment_rad
    surface = earth.ROTATION_RATE_RAD_S * earth.RADIUS_M * math.cos(13.0 * DEG)
    assert np.all(np.diff(mu) < 0)
    assert np.all(mu <= np.arcsin(surface / speeds) * (1 + 1e-12))


def test_tangent_velocity_lies_along_the_cross_track_drag():
    """V_tangent is normal to V, in the plane of Vrel and V, on the side of the drag -Vrel."""
    launch = _launch(1800.0, 85.0, 109.0, 13.0)
    corrected = launch.relative_m_s + launch.surface_m_s
    direction = eci.tangent_direction(launch.relative_m_s, corrected)
    assert np.linalg.norm(direction) == pytest.approx(1.0)
    assert direction @ corrected == pytest.approx(0.0, abs=1e-9)
    assert np.linalg.det(np.stack([direction, corrected, launch.relative_m_s])) == pytest.approx(
        0.0, abs=1e-6
    )
    assert direction @ -launch.relative_m_s > 0
    # so adding it turns V further from Vrel: lower and more eastward for this shot
    with_tangent = _launch(1800.0, 85.0, 109.0, 13.0, model=eci.CONSISTENT)
    without = _launch(1800.0, 85.0, 109.0, 13.0, model=NO_TANGENT)
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
    launch = baseline_chapter_4(45.0, bearing_deg=1.0 / DEG, latitude_deg=0.7 / DEG)
    reference = mks.for_launch(launch)
    air = get_atmosphere("two_segment")  # the launch's air at the gun: Cd0's Mach
    cd0 = BASELINE.drag_law(2157.0 / air.speed_of_sound(0.0))
    solution = eci.correction_for_arrays(
        2157.0,
        45 * DEG,
        1.0,
        0.7,
        drag_area_m2=cd0 * BASELINE.reference_area_m2,
        mass_kg=BASELINE.mass_kg,
        surface_density_kg_m3=1.225,  # the MKS's air, eq 3.11 (mks.gun_density_kg_m3)
        rotation_rate_rad_s=0.0,
    ).solution()
    # the launch's own ECI MKS: its rotation_rate_rad_s is 0 unless the launch says otherwise
    by_launch = eci.correction_for_launch(launch).solution()
    for name in ("h_inf", "c1", "c2", "amplitudes", "beta", "tau"):
        assert getattr(solution, name) == pytest.approx(getattr(reference, name), rel=1e-9), name
        assert getattr(by_launch, name) == pytest.approx(getattr(reference, name), rel=1e-9), name
    assert solution.apogee_altitude() == pytest.approx(reference.apogee_altitude(), rel=1e-9)
    assert by_launch.apogee_altitude() == pytest.approx(reference.apogee_altitude(), rel=1e-9)


@pytest.mark.parametrize("model", ["consistent", "dissertation", "printed_columns"])
def test_correction_for_launch_is_correction_for_arrays_of_its_fields(model):
    """Barbados, 1800 m/s at 85 deg on bearing 109 deg, the Earth turning: the Launch's speed,
    angles, Cd0 A at its Mach, mass, air at the gun and rotation, nothing else."""
    launch = baseline_chapter_4(
        85.0,
        speed_m_s=1800.0,
        bearing_deg=109.0,
        latitude_deg=BARBADOS.latitude_rad / DEG,
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
    )
    by_launch = eci.correction_for_launch(launch, model)
    air = get_atmosphere("two_segment")
    explicit = eci.correction_for_arrays(
        1800.0,
        85 * DEG,
        109 * DEG,
        BARBADOS.latitude_rad,
        drag_area_m2=BASELINE.drag_law(1800.0 / air.speed_of_sound(0.0))
        * BASELINE.reference_area_m2,
        mass_kg=BASELINE.mass_kg,
        surface_density_kg_m3=1.225,  # the MKS's air, eq 3.11 (mks.gun_density_kg_m3)
        model=model,
    )
    assert by_launch.model is eci.get_model(model)
    for name in ("velocity_m_s", "misalignment_rad", "beta", "tau", "speed_ratio_squared"):
        assert getattr(by_launch, name) == pytest.approx(getattr(explicit, name), rel=1e-12), name
    # and it keeps what it was computed from, to lay the same gun at other angles
    for name in ("drag_area_m2", "mass_kg", "surface_density_kg_m3", "rotation_rate_rad_s"):
        assert getattr(by_launch, name) == pytest.approx(getattr(explicit, name), rel=1e-12), name
    assert by_launch.rotation_rate_rad_s == earth.ROTATION_RATE_RAD_S
    solution = eci.correction_for_launch(launch, model).solution()
    assert solution.apogee_altitude() == pytest.approx(
        explicit.solution().apogee_altitude(), rel=1e-12
    )


def test_correction_for_launch_takes_each_rounds_mass_drag_and_air():
    """Rounds of one gun with their own masses, one drag area and a site's air: eq 6.11's beta
    goes as Cd0 A rho0 / m, and the launch geometry (mu, V_tangent's direction) is the gun's."""
    speeds, masses = np.array([1800.0, 1900.0, 2000.0]), np.array([77.6, 83.9, 84.4])
    rounds = Launches(
        BASELINE,
        speeds,
        85.0,
        bearing_deg=109.0,
        latitude_deg=BARBADOS.latitude_rad / DEG,
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
    )
    given = dict(mass_kg=masses, drag_area_m2=2.85e-3, surface_density_kg_m3=1.14)
    by_launch = eci.correction_for_launch(rounds, "dissertation", **given)
    explicit = eci.correction_for_arrays(
        speeds, 85 * DEG, 109 * DEG, BARBADOS.latitude_rad, model="dissertation", **given
    )
    for name in ("velocity_m_s", "misalignment_rad", "beta", "tau", "mass_kg"):
        assert getattr(by_launch, name) == pytest.approx(getattr(explicit, name), rel=1e-12), name
    heavier = eci.correction_for_launch(rounds, "dissertation", **{**given, "mass_kg": 2 * masses})
    assert heavier.beta == pytest.approx(by_launch.beta / 2, rel=1e-12)
    assert heavier.misalignment_rad == pytest.approx(by_launch.misalignment_rad, rel=1e-12)
    own = eci.correction_for_launch(rounds, "dissertation")  # the cone's mass and 1.225 kg/m^3
    assert own.beta * own.mass_kg / own.drag_area_m2 == pytest.approx(
        by_launch.beta * masses / 2.85e-3 * 1.225 / 1.14, rel=1e-12
    )


def test_launch_entry_points_refuse_what_the_eci_mks_cannot_fly():
    with pytest.raises(TypeError, match="Launch"):
        eci.correction_for_launch(BASELINE)
    with pytest.raises(ValueError, match="site_altitude_m"):
        eci.correction_for_launch(baseline_chapter_4(45.0, site_altitude_m=1000.0))
    with pytest.warns(ModelValidityWarning, match="cross_wind_m_s"):
        eci.correction_for_launch(HP_CHAPTER_2)


@pytest.mark.parametrize("decay", ["printed", "consistent"])
def test_eci_solution_scales(decay):
    model = replace(eci.CONSISTENT, name=decay, decay=decay)
    launch = _launch(1800.0, 85.0, 109.0, 13.0, model=model)
    solution = eci.correction_for_arrays(
        1800.0,
        85 * DEG,
        109 * DEG,
        13 * DEG,
        drag_area_m2=2.7e-3,
        mass_kg=84.0,
        surface_density_kg_m3=1.225,
        model=model,
    ).solution()
    cos_mu = math.cos(launch.misalignment_rad)
    assert solution.drive_scale[0, 0] == pytest.approx(cos_mu * launch.speed_ratio_squared)
    expected = cos_mu * (launch.speed_ratio_squared if decay == "consistent" else 1.0)
    assert solution.decay_scale[0, 0] == pytest.approx(expected)
    assert solution.h_inf[0, 0] == pytest.approx(launch.asymptotic_angular_momentum_m2_s)


def test_dissertation_model_takes_each_angle_where_it_says():
    """beta at the gun's elevation, tau and eq 5.8's climb at the corrected one, (Vrel/V)^2 of
    the launch velocity (V_tangent included) by eq 5.3."""
    launch = _launch(1800.0, 85.0, 109.0, 13.0, model=eci.DISSERTATION)
    gun, corrected = 85 * DEG, launch.corrected_elevation_rad
    # written out, not read from the package: a slip in eqs 3.22, 3.27 or 5.8 fails here
    k, radius = 1.17e-4, 6_378_000.0  # the text's 0.117 /km; Appendix A's R
    drag = 2.7e-3 * 1.225  # Cd A rho0
    assert launch.beta == pytest.approx(drag / (2 * k * 84.0 * math.sin(gun)), rel=1e-13)  # 3.22
    assert launch.tau == pytest.approx(k * radius * math.tan(corrected), rel=1e-13)  # eq 3.27
    assert launch.tangent_speed_m_s == pytest.approx(  # eq 5.8
        drag * math.sin(launch.misalignment_rad) * 1800.0 / (2 * 84.0 * k * math.sin(corrected)),
        rel=1e-13,
    )
    assert launch.speed_ratio_squared == pytest.approx(
        eci.speed_ratio_squared_eq_5_3(launch.velocity_m_s, 13 * DEG), rel=1e-12
    )
    assert launch.beta_column == pytest.approx(launch.beta * math.cos(launch.misalignment_rad))


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: eci.get_model("newtonian"), "model"),
        (lambda: replace(eci.CONSISTENT, decay="exact"), "decay"),
        (lambda: eci.relative_velocity(1800.0, 1.4, 2 * math.pi, 0.2), "bearing_rad"),
        (lambda: eci.relative_velocity(1800.0, 1.4, 1.0, 91 * DEG), "latitude_rad"),
        (lambda: eci.surface_velocity(91 * DEG), "latitude_rad"),
        (lambda: _launch(float("nan"), 85.0, 109.0, 13.0), "speed_m_s"),
        (
            lambda: eci.correction_for_arrays(
                1800.0, 1.4, 1.0, 0.2, drag_area_m2=-1.0, mass_kg=84.0, surface_density_kg_m3=1.2
            ),
            "drag_area_m2",
        ),
    ],
)
def test_bad_input_is_named(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_a_launch_is_not_checked_again_on_its_way_in(monkeypatch):
    """A Launch's values were checked when it was made: its door checks only what it is given
    beside it (here nothing), while the door for loose arrays checks each."""

    class Refusing(Bounds):
        def check(self, value, name):
            raise AssertionError("checked again")

    launch = baseline_chapter_4(60.0, bearing_deg=109.0, latitude_deg=13.1)
    monkeypatch.setattr(eci, "Bounds", Refusing)
    eci.correction_for_launch(launch)
    with pytest.raises(AssertionError, match="checked again"):
        eci.correction_for_launch(launch, mass_kg=80.0)
    with pytest.raises(AssertionError, match="checked again"):
        _launch(1800.0, 85.0, 109.0, 13.0)
