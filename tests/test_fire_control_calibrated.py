"""Fire control on the calibrated MKS (issue 35, item 4): its roots flown by the 3DOF land on
targets it was never calibrated on, the default model is the text's ECI MKS unchanged, and a
bad model or a gun outside the calibrated band is refused by name (its crossing of an altitude,
which the roots rest on: tests/test_calibrated_mks.py)."""

import dataclasses

import numpy as np
import pytest

from harp_analysis.analyses.fire_control.firing import (
    BARBADOS_HP,
    barbados_case,
    destination,
    firing_solutions,
)
from harp_analysis.analyses.fire_control.intercepts import raid, raid_windows
from harp_analysis.analyses.fire_control.verification import verify_with_3dof
from harp_analysis.engines import threedof
from harp_analysis.models.trajectory import rotate_about_axis

GUN = BARBADOS_HP
#: Aims no launch of the calibration's grid was flown at: (bearing deg, downrange m, altitude m,
#: branch), both roots of each.
AIMS = [
    (37.0, 123e3, 0.0, "descending"),
    (251.0, 207e3, 31.4e3, "descending"),
    (305.0, 161e3, 52.7e3, "descending"),
    (140.0, 61e3, 23.7e3, "ascending"),
]


def _three_dof_miss(root, target) -> float:
    """The 3DOF flown whole at ``root`` (simulate_3dof's table, every 0.02 s): the distance (m)
    from the target of where its path crosses the target's altitude on the root's branch,
    interpolated linearly between the rows and turned with the Earth to its fixed frame."""
    flight = threedof.simulate_3dof(
        GUN.but(elevation_deg=root.elevation_deg, bearing_deg=root.bearing_deg),
        output_step_s=0.02,
    )
    altitude = flight.altitude_m.to_numpy() - target.altitude_m
    top = int(np.argmax(altitude))
    side = slice(0, top + 1) if root.branch == "ascending" else slice(top, None)
    rows = np.arange(len(flight))[side]
    crossed = rows[:-1][np.sign(altitude[rows[:-1]]) != np.sign(altitude[rows[1:]])]
    if not crossed.size and root.branch == "descending" and target.altitude_m == 0.0:
        crossed = np.array([len(flight) - 2])  # the table ends on the ground
    i = int(crossed[0])
    share = altitude[i] / (altitude[i] - altitude[i + 1])
    table = flight[["time_s", "x_m", "y_m", "z_m"]].to_numpy()
    t, *inertial = (1 - share) * table[i] + share * table[i + 1]
    fixed = rotate_about_axis(np.array(inertial)[:, None], np.array([-GUN.rotation_rate_rad_s * t]))
    return float(np.linalg.norm(fixed[:, 0] - target.earth_fixed_m()))


@pytest.fixture(scope="module")
def uncalibrated_aims():
    cases = []
    for bearing, downrange, altitude, branch in AIMS:
        target = destination(GUN, bearing, downrange, altitude)
        cases.append(
            (
                target,
                firing_solutions(GUN, target, branch=branch),
                firing_solutions(GUN, target, branch=branch, model="calibrated"),
            )
        )
    return cases


def test_calibrated_roots_land_the_3dof_within_100_m_of_aims_never_calibrated_on(uncalibrated_aims):
    """Each root the calibrated MKS gives, flown by the 3DOF on its own (simulate_3dof, its
    crossing found here), lands within 100 m of the target (6-55 m), where the ECI MKS's root of
    the same target misses by hundreds of metres to kilometres."""
    for target, text, calibrated in uncalibrated_aims:
        assert len(calibrated.roots) == len(text.roots) >= 1, calibrated.reason
        for ours, theirs in zip(calibrated.roots, text.roots, strict=True):
            assert ours.model == "calibrated" and ours.reason is None, ours.reason
            assert theirs.model == "eci"
            assert ours.miss_m < 0.01  # the calibrated MKS's own root
            assert _three_dof_miss(ours, target) < 100.0
            assert _three_dof_miss(theirs, target) > 300.0  # 0.35-22 km


def test_the_3dof_refinement_lands_a_calibrated_root_in_two_flights(uncalibrated_aims):
    """The calibrated root carries the calibrated MKS's own Jacobian: the 3DOF's refinement
    lands within a metre with one Newton step after its check flight; from the ECI MKS's root,
    with the ECI MKS's Jacobian, it takes more."""
    for target, text, calibrated in uncalibrated_aims[:2]:
        for ours, theirs in zip(calibrated.roots, text.roots, strict=True):
            from_ours = verify_with_3dof(GUN, target, ours, tolerance_m=1.0)
            from_theirs = verify_with_3dof(GUN, target, theirs, tolerance_m=1.0)
            assert from_ours.converged and from_ours.flights == 2, from_ours
            assert from_theirs.flights > 2


def test_the_default_model_is_the_text_s_eci_mks():
    """By default the roots are the ECI MKS's own: its flight at each lands on the target (the
    solver's tolerance), and no calibration is asked for."""
    gun, target = barbados_case()
    result = firing_solutions(gun, target)
    assert result == firing_solutions(gun, target, model="eci")
    assert len(result.roots) == 2
    for root in result.roots:
        assert root.model == "eci" and root.reason is None
        assert root.miss_m < 0.01


def test_a_root_below_the_calibrated_band_keeps_the_eci_root_and_says_why():
    """25 km out at sea level the low root is a few degrees up, below the 15 deg the table
    was learned from: the ECI MKS's root stands, with the reason; the high root is calibrated."""
    target = destination(GUN, 200.0, 25e3)
    text = firing_solutions(GUN, target)
    result = firing_solutions(GUN, target, model="calibrated")
    # the ECI MKS's root, its count of MKS solves the calibrated MKS's tries added
    searched, why = result.low.mks_solves, result.low.reason
    assert result.low == dataclasses.replace(text.low, reason=why, mks_solves=searched)
    assert searched > text.low.mks_solves
    assert result.low.model == "eci" and result.low.elevation_deg < 15.0
    assert "below 15 deg of elevation" in result.low.reason
    assert "outside the band" in result.low.reason
    assert result.high.model == "calibrated" and result.high.reason is None


def test_a_bad_model_or_a_gun_outside_the_band_is_refused_by_name():
    gun, target = barbados_case()
    with pytest.raises(ValueError, match="unknown model '6dof'; expected one of 'eci', 'calib"):
        firing_solutions(gun, target, model="6dof")
    with pytest.raises(ValueError, match="unknown model 'calibrated MKS'"):
        raid_windows(gun, raid(gun, 1), count=2, model="calibrated MKS")
    slow, near = gun.but(speed_m_s=1500.0), destination(gun, 109.0, 60e3)
    with pytest.raises(ValueError, match="speed_m_s = 1500 m/s lies outside the band"):
        firing_solutions(slow, near, model="calibrated")
    assert firing_solutions(slow, near).roots  # the ECI MKS flies it
