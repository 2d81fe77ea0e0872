"""One physics suite run over every engine of :mod:`harp_analysis.engines.catalogue` (as
py-ballisticcalc runs its suite once per engine).

Each engine flies the same :class:`~harp_analysis.models.launch.Launch` and returns the same table
and metadata, under the label its record gives. Checked against physics, not against any engine's
earlier output, and each capability the record claims checked in flight:

- in vacuum every engine flies the closed-form Kepler conic (:mod:`harp_analysis.engines.kepler`);
- in vacuum the specific energy v^2/2 - GM/r is conserved along the flight;
- a cross wind from the left mirrors one from the right (the engines that model wind; the others
  say they leave it out);
- on the turning Earth a shot due north bends to the right (the engines that fly it; the others
  refuse it);
- a rigid-body engine refuses a projectile without Appendix B's tables, the others fly it;
- a batch flies each launch as it flies alone (the engines that fly batches);
- a day with denser air flies as a lighter projectile does (drag is rho A / m; the engines that
  model the day's air);
- the result converges as the engine's numerical tolerance tightens.

The ECI MKS flies its own table; on a still Earth it is the MKS's, and on a turning Earth in
vacuum it is the rotating 3DOF's, frame and all.
"""

import dataclasses
import math
import warnings

import numpy as np
import pytest

import harp_analysis
from harp_analysis.engines import catalogue, eci, kepler, mks, mks_improved, threedof
from harp_analysis.engines.flight_grid import DEFAULT_GRID, Grid
from harp_analysis.foundation import earth
from harp_analysis.foundation.validation import ModelValidityWarning
from harp_analysis.models.launch import (
    HP_CHAPTER_2,
    LP_CHAPTER_2,
    Launches,
    baseline_chapter_4,
    chapter_2,
)
from harp_analysis.models.projectiles import BASELINE, HP
from harp_analysis.models.trajectory import BASE_COLUMNS, METADATA_KEYS

#: The learned tables' tolerance: the grid of the 3DOF flights they learn from, coarse to the
#: default.
LEARNED_GRIDS = (
    Grid(elevations_deg=(15.0, 40.0, 65.0, 88.0), speed_step=0.35),
    Grid(elevations_deg=(15.0, 25.0, 35.0, 50.0, 65.0, 80.0, 88.0), speed_step=0.2),
    Grid(elevations_deg=(15.0, 20.0, 25.0, 30.0, 37.0, 45.0, 55.0, 65.0, 75.0, 84.0, 88.0)),
    DEFAULT_GRID,
)
#: The suite runs over every engine of the catalogue; what follows are the suite's own numbers,
#: by engine name: each engine's tolerance option, loosest first, for the convergence check,
#: how close to the conic its numerics come in vacuum (m), how well it keeps the energy
#: (relative), and the options it cannot fly without.
TOLERANCE_STEPS = {
    "3dof": (1e-6, 1e-8, 1e-10, 1e-12),
    "6dof": (1e-6, 1e-8, 1e-10, 1e-12),
    "mlt": (4000.0, 2000.0, 1000.0, 250.0),
    "mks": (1, 2, 3, 8),
    "eci_mks": (1, 2, 3, 8),
    "appendix_a": (0.08, 0.04, 0.02, 0.005),
    "calibrated_mks": LEARNED_GRIDS,
    "flyout_table": LEARNED_GRIDS,
}
VACUUM_TOLERANCE_M = {
    "mlt": 50.0,
    "appendix_a": 300.0,
    "flyout_table": 10.0,  # its cubics across the grid's elevations and speeds: metres of range
}  # others 1 mm
ENERGY_TOLERANCE = {
    "mlt": 1e-8,  # gravity frozen over each segment
    "calibrated_mks": 1e-6,  # in vacuum its table learns the 3DOF's own error (rtol 1e-9)
    "flyout_table": 1e-6,  # its velocity the spline's rate, interpolated across nodes: cm/s
    "appendix_a": 1e-5,  # its speed is a backward difference half a step old: an error g dt V
}  # others 1e-9
REQUIRED_OPTIONS = {"appendix_a": {"dt_s": 0.01}}  # the text prints no step
#: The learned tables fly the denser day from the heavier gun's table and the lighter round
#: from its own: alike to what a table holds (metres, seconds' hundredths), not to rtol.
DAY_TOLERANCE = {"calibrated_mks": 2e-4, "flyout_table": 2e-4}

ENGINES = list(catalogue.ENGINES.values())
VACUUM = chapter_2(
    HP,
    atmosphere="vacuum",
    cross_wind_m_s=0.0,
    spin_rad_s=0.0,
    speed_m_s=1500.0,
    elevation_deg=45.0,
)


def _fly(engine, launch, **options):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)
        return engine.fly(launch, **{**REQUIRED_OPTIONS.get(engine.name, {}), **options})


@pytest.fixture(scope="module", params=ENGINES, ids=lambda e: e.name)
def engine(request):
    return request.param


#: Where an engine flies only a band of launches (the calibrated MKS: 0.8-1.15 of the
#: projectile's muzzle speed), its vacuum launch is in the band.
_VACUUM_FOR = {
    name: VACUUM.but(speed_m_s=HP.launch_speed_m_s) for name in ("calibrated_mks", "flyout_table")
}


def _vacuum(engine):
    return _VACUUM_FOR.get(engine.name, VACUUM)


@pytest.fixture(scope="module")
def vacuum_flight(engine):
    return _fly(engine, _vacuum(engine))


def test_the_catalogue_holds_each_engine_once_under_its_name():
    assert catalogue.ENGINE_NAMES == tuple(engine.name for engine in ENGINES)
    assert len({engine.label for engine in ENGINES}) == len(ENGINES)
    assert set(TOLERANCE_STEPS) == set(catalogue.ENGINE_NAMES)  # the suite knows every engine
    for engine in ENGINES:
        assert catalogue.get_engine(engine.name) is engine
    with pytest.raises(ValueError, match="unknown engine '4dof'; expected one of '3dof'"):
        catalogue.get_engine("4dof")


def test_fly_is_the_engine_s_own_flight():
    table = harp_analysis.fly(HP_CHAPTER_2, "mks", n_terms=2, warn=False)
    assert table.equals(mks.simulate_mks(HP_CHAPTER_2, n_terms=2, warn=False))
    assert harp_analysis.fly(HP_CHAPTER_2).attrs["engine"] == "3DOF"  # the default engine
    assert harp_analysis.get_engine("6dof") is catalogue.ENGINES["6dof"]


def test_same_table_and_metadata(engine, vacuum_flight):
    columns = (
        BASE_COLUMNS
        if engine.full_table
        else (
            "time_s",
            "altitude_m",
            "ground_range_m",
            "cross_range_m",
            "speed_m_s",
            "specific_angular_momentum_m2_s",
        )
    )
    assert set(columns) <= set(vacuum_flight.columns)
    assert engine.full_table == (set(BASE_COLUMNS) <= set(vacuum_flight.columns))
    assert set(METADATA_KEYS) <= set(vacuum_flight.attrs)
    assert vacuum_flight.attrs["engine"] == engine.label
    assert vacuum_flight.attrs["launch"] == _vacuum(engine)
    assert vacuum_flight.attrs["stop_reason"] == "impact" and vacuum_flight.attrs["impact"]


def test_vacuum_flight_is_the_kepler_conic(engine, vacuum_flight):
    launch = _vacuum(engine)
    conic = kepler.ballistic_conic(launch.speed_m_s, launch.elevation_rad)
    attrs = vacuum_flight.attrs
    tolerance = VACUUM_TOLERANCE_M.get(engine.name, 1e-3)
    assert attrs["apogee_altitude_m"] == pytest.approx(
        float(conic.apogee_altitude_m), abs=tolerance
    )
    assert attrs["range_m"] == pytest.approx(float(conic.ground_range_m), abs=tolerance)
    if engine.full_table:
        assert attrs["time_of_flight_s"] == pytest.approx(float(conic.time_of_flight_s), abs=1e-3)


def test_vacuum_energy_is_conserved(engine, vacuum_flight):
    radius = vacuum_flight.altitude_m + earth.RADIUS_M
    energy = 0.5 * vacuum_flight.speed_m_s**2 - earth.GM_M3_S2 / radius
    launch = 0.5 * _vacuum(engine).speed_m_s ** 2 - earth.GM_M3_S2 / earth.RADIUS_M
    tolerance = ENERGY_TOLERANCE.get(engine.name, 1e-9)
    assert np.max(np.abs(energy - launch)) <= tolerance * abs(launch)


def _mirrored(launch):
    """The launch seen in a mirror through its vertical plane: the wind from the other side, the
    spin the other way, and a finned projectile's fins canted the other way (they roll it)."""
    projectile = launch.projectile
    if projectile.aero is not None:
        aero = dataclasses.replace(projectile.aero, cldd=tuple(-c for c in projectile.aero.cldd))
        projectile = dataclasses.replace(projectile, name=f"{projectile.name} mirrored", aero=aero)
    return launch.but(
        projectile=projectile, cross_wind_m_s=-launch.cross_wind_m_s, spin_rad_s=-launch.spin_rad_s
    )


def test_cross_wind_from_the_left_mirrors_one_from_the_right(engine):
    left = _fly(engine, HP_CHAPTER_2)
    right = _fly(engine, _mirrored(HP_CHAPTER_2))
    # equal to the integrators' tolerance (rtol 1e-9 of a 240 km flight)
    assert left.attrs["range_m"] == pytest.approx(right.attrs["range_m"], abs=1e-3)
    assert left.attrs["cross_range_m"] == pytest.approx(-right.attrs["cross_range_m"], abs=1e-3)
    if engine.wind:
        assert left.attrs["cross_range_m"] > 10.0  # blown toward positive cross range
    else:
        assert left.attrs["cross_range_m"] == pytest.approx(0.0, abs=1e-9)


def test_an_engine_without_wind_says_it_leaves_it_out(engine):
    if engine.wind:
        pytest.skip(f"the {engine.label} flies the wind")
    with pytest.warns(ModelValidityWarning, match="cross_wind_m_s"):
        engine.fly(HP_CHAPTER_2, **REQUIRED_OPTIONS.get(engine.name, {}))


@pytest.mark.parametrize(
    "fly", [mks.for_launch, eci.correction_for_launch], ids=["MKS solution", "ECI correction"]
)
def test_the_mks_solutions_without_wind_say_they_leave_it_out(fly):
    with pytest.warns(ModelValidityWarning, match="cross_wind_m_s"):
        fly(HP_CHAPTER_2)


def test_a_shot_north_on_the_turning_earth_bends_right_or_is_refused(engine):
    """In vacuum the Coriolis acceleration -2 omega x v deflects a northward shot of the
    northern hemisphere to the east, the right of its line of fire (kilometres for this
    three-minute flight); an engine that cannot fly the turning Earth refuses it by name."""
    northward = _vacuum(engine).but(
        latitude_deg=45.0, bearing_deg=0.0, rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S
    )
    if not engine.rotating_earth:
        with pytest.raises(ValueError, match="rotation_rate_rad_s"):
            _fly(engine, northward)
        return
    assert _fly(engine, northward).attrs["cross_range_m"] > 1000.0
    assert _fly(engine, _vacuum(engine)).attrs["cross_range_m"] == pytest.approx(0.0, abs=1e-6)


def test_a_rigid_body_engine_refuses_a_point_mass_and_the_others_fly_it(engine):
    """The baseline cone has a drag law but no aerodynamic tables or inertias."""
    cone = chapter_2(BASELINE, cross_wind_m_s=0.0, spin_rad_s=0.0)
    if engine.rigid_body:
        with pytest.raises(ValueError, match="aerodynamic tables"):
            _fly(engine, cone)
        return
    assert _fly(engine, cone).attrs["impact"]


def test_a_batch_flies_each_launch_as_it_flies_alone(engine):
    if not engine.batch:
        pytest.skip(f"the {engine.label} flies one launch at a time")
    launches = [HP_CHAPTER_2.but(elevation_deg=elevation) for elevation in (30.0, 50.0, 70.0)]
    rows = engine.fly_batch(Launches.from_launches(launches))
    for row, launch in zip(rows.itertuples(), launches, strict=True):
        alone = _fly(engine, launch).attrs
        for key in ("apogee_altitude_m", "range_m", "time_of_flight_s", "impact_speed_m_s"):
            assert getattr(row, key) == pytest.approx(alone[key], rel=1e-12), key


def test_converges_as_the_tolerance_tightens(engine):
    launch = chapter_2(HP)
    apogees = [
        _fly(engine, launch, **{engine.tolerance: value}).attrs["apogee_altitude_m"]
        for value in TOLERANCE_STEPS[engine.name]
    ]
    differences = [abs(a - apogees[-1]) for a in apogees[:-1]]
    assert differences[0] > differences[-1]
    assert all(math.isfinite(a) for a in apogees)


def test_a_denser_day_flies_as_a_lighter_projectile(engine):
    """Drag per unit mass is rho Cd A / (2 m): 8 % more air at every height is 8 % less mass
    (Cd depends on Mach alone, which the density does not change)."""
    if not engine.day_air:
        with pytest.warns(ModelValidityWarning, match="density_change_fraction"):
            engine.fly(HP_CHAPTER_2.but(density_change_fraction=0.08))
        return
    lighter = dataclasses.replace(HP, name="HP lighter", mass_kg=HP.mass_kg / 1.08)
    # At rtol 1e-9 the 3DOF lands each within about 1.5e-8 of its range, on step sequences of
    # their own (measured against rtol 1e-13): flown at 1e-11, alike well within 1e-8
    options = {"rtol": 1e-11} if engine.tolerance == "rtol" else {}
    denser_day = _fly(engine, HP_CHAPTER_2.but(density_change_fraction=0.08), **options).attrs
    light_round = _fly(engine, HP_CHAPTER_2.but(projectile=lighter), **options).attrs
    normal = _fly(engine, HP_CHAPTER_2).attrs
    assert denser_day["apogee_altitude_m"] < normal["apogee_altitude_m"] - 100.0
    for key in ("apogee_altitude_m", "range_m", "time_of_flight_s"):
        assert denser_day[key] == pytest.approx(
            light_round[key], rel=DAY_TOLERANCE.get(engine.name, 1e-8)
        )


# --- the ECI MKS's table against the MKS's and the rotating 3DOF's --------------------------------
@pytest.mark.parametrize(
    "launch",
    [
        HP_CHAPTER_2,  # its wind left out by both
        baseline_chapter_4(30.0, bearing_deg=17.0, latitude_deg=-33.0, longitude_deg=151.2),
        VACUUM,
    ],
    ids=["HP", "baseline, off the equator", "vacuum"],
)
def test_the_eci_mks_on_a_still_earth_flies_the_mks_table(launch):
    """Without the Earth's rotation omega x r0 and V_tangent vanish, mu = 0 and (Vrel/V)^2 =
    1: eqs 6.6-6.15 are the MKS's constants, so every row and every number of the metadata."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelValidityWarning)  # the wind both leave out
        still = eci.simulate_eci_mks(launch, warn=False)
        flat = mks.simulate_mks(launch, warn=False)
    assert list(still.columns) == list(flat.columns)
    for column in BASE_COLUMNS:
        np.testing.assert_allclose(still[column], flat[column], rtol=1e-12, atol=1e-6)
    for key in METADATA_KEYS[1:]:
        expected = flat.attrs[key]
        if isinstance(expected, float):
            expected = pytest.approx(expected, rel=1e-12, abs=1e-6)
        assert still.attrs[key] == expected, key


#: A shot from Barbados (its longitude, the HP's muzzle speed) on the turning Earth in vacuum,
#: where the ECI MKS is exact: the inertial conic of Vrel + omega x r0 (no drag, no V_tangent).
TURNING_VACUUM = VACUUM.but(
    latitude_deg=13.08,
    longitude_deg=-59.6,
    bearing_deg=109.0,
    elevation_deg=60.0,
    rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
)


def test_the_eci_mks_on_a_turning_earth_in_vacuum_flies_the_rotating_3dof():
    """The same frame as the 3DOF's: inertial positions in the Earth's axes at launch, ranges
    on the turning Earth, Mach on the speed relative to the turning air. At the 3DOF's own
    times (placed on :data:`eci.TIME_GRID_POINTS` angles: millimetres here), and the metadata's
    apogee and impact."""
    flight = threedof.simulate_3dof(TURNING_VACUUM, output_step_s=2.0)
    table = eci.simulate_eci_mks(TURNING_VACUUM, times_s=flight.time_s)
    both = table.iloc[:-1]  # at the 3DOF's times; the last row is the impact
    assert len(both) >= len(flight) - 1
    flown = flight.iloc[: len(both)]
    np.testing.assert_allclose(both.time_s, flown.time_s, rtol=0, atol=0)
    position = both[["x_m", "y_m", "z_m"]].to_numpy() - flown[["x_m", "y_m", "z_m"]].to_numpy()
    assert np.max(np.linalg.norm(position, axis=1)) < 0.01
    for column, tolerance in (
        ("altitude_m", 0.01),
        ("ground_range_m", 0.01),
        ("cross_range_m", 0.01),
        ("speed_m_s", 1e-4),
        ("mach", 1e-7),
        ("specific_angular_momentum_m2_s", 1e-9 * float(flown.specific_angular_momentum_m2_s[0])),
        ("flight_path_angle_rad", 1e-8),
    ):
        np.testing.assert_allclose(both[column], flown[column], rtol=0, atol=tolerance)
    assert abs(flight.attrs["cross_range_m"]) > 1e3  # the turning Earth moves the impact
    for key, tolerance in (
        ("apogee_altitude_m", 1e-4),
        ("apogee_time_s", 1e-6),
        ("apogee_ground_range_m", 1e-4),
        ("time_of_flight_s", 1e-6),
        ("range_m", 1e-4),
        ("cross_range_m", 1e-4),
        ("impact_speed_m_s", 1e-4),
    ):
        assert table.attrs[key] == pytest.approx(flight.attrs[key], abs=tolerance), key


def test_the_eci_mks_table_names_what_it_cannot_take():
    with pytest.raises(ValueError, match="times_s"):
        eci.simulate_eci_mks(TURNING_VACUUM, times_s=[3.0, 1.0])
    with pytest.raises(ValueError, match="n_points"):
        eci.simulate_eci_mks(TURNING_VACUUM, n_points=1)
    with pytest.raises(TypeError, match="launch must be a Launch"):
        eci.simulate_eci_mks([TURNING_VACUUM])
    with pytest.raises(ValueError, match="escapes"):
        eci.simulate_eci_mks(TURNING_VACUUM.but(speed_m_s=12e3), warn=False)


# --- every engine over the launches it accepts -------------------------------------------------
def _improved_mks(launch):
    solution = mks_improved.solve(launch)
    return {"apogee_altitude_m": solution.apogee_altitude_m, "range_m": solution.impact_range_m[0]}


#: Every engine of the catalogue and the MKS solutions without a table of their own, with their
#: validity warnings recorded.
_GRID_ENGINES = {
    **{
        engine.name: lambda launch, engine=engine: engine.fly(
            launch, **REQUIRED_OPTIONS.get(engine.name, {})
        )
        for engine in ENGINES
    },
    "improved_mks": _improved_mks,
}
#: What each engine is checked against: the 6DOF for linear theory (its own equations with
#: products dropped), the 3DOF for the point-mass models, and each other for the simulations.
_REFERENCE = {"3dof": "6dof", "6dof": "3dof", "mlt": "6dof"}
#: The elevations and speeds a Launch accepts, from grazing to almost vertical and from
#: subsonic to beyond HP's, for the two rigid bodies every engine flies; windless, so that no
#: engine's warning that it ignores the wind can excuse a wrong result.
_GRID = [
    base.but(speed_m_s=speed, elevation_deg=elevation, cross_wind_m_s=0.0)
    for base in (HP_CHAPTER_2, LP_CHAPTER_2)
    for speed in (300.0, 1000.0, 2000.0)
    for elevation in (0.01, 5.0, 45.0, 70.0, 88.0, 89.9)
]
#: Agreement without a warning: within 3 % and 300 m of the reference's apogee and range.
_AGREEMENT = {"rel": 0.03, "abs": 300.0}
#: A refusal must say what it refuses: the launch's field, the model or its parameter.
_NAMED = ("elevation", "speed", "segment_length_m", "beta", "MKS", "MLT", "escape")
_OBSCURE = ("ZeroDivisionError", "OverflowError", "FloatingPointError", "RuntimeError")


def _outcome(fly, launch):
    """(apogee, range) with the validity warnings raised, or the error's message (its type
    first, if it is not the ValueError of a refusal)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = fly(launch)
        except ValueError as error:
            return None, [], str(error)
        except Exception as error:  # obscure whatever it says
            return None, [], f"{type(error).__name__}: {error}"
    attrs = result if isinstance(result, dict) else result.attrs
    flagged = [w for w in caught if issubclass(w.category, ModelValidityWarning)]
    return (attrs["apogee_altitude_m"], attrs["range_m"]), flagged, None


@pytest.fixture(scope="module")
def grid_outcomes():
    return {
        (name, index): _outcome(fly, launch)
        for name, fly in _GRID_ENGINES.items()
        for index, launch in enumerate(_GRID)
    }


@pytest.mark.parametrize("name", list(_GRID_ENGINES))
def test_every_engine_over_the_launch_grid_agrees_warns_or_refuses_by_name(name, grid_outcomes):
    """Issue 25: nothing flies silently wrong. Each launch of the grid is flown within the
    reference's tolerance, or warned of (ModelValidityWarning, truncated flights included),
    or refused with a message that names what it refuses."""
    silent, obscure = [], []
    for index, launch in enumerate(_GRID):
        result, flagged, error = grid_outcomes[name, index]
        where = f"{launch.projectile.name} {launch.speed_m_s:g} m/s {launch.elevation_deg:g} deg"
        if error is not None:
            if error.split(":")[0] in _OBSCURE or not any(word in error for word in _NAMED):
                obscure.append(f"{where}: {error}")
            continue
        if flagged:
            continue
        reference, _, _ = grid_outcomes[_REFERENCE.get(name, "3dof"), index]
        if reference is None:
            continue
        if result != pytest.approx(reference, **_AGREEMENT):
            silent.append(f"{where}: {result} against {reference}")
    assert not obscure, obscure
    assert not silent, silent
