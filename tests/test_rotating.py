"""Chapter 5's comparison: the ECI MKS tracks the rotating 3DOF, and the printed eq 6.14 does
not. Thresholds are the text's reproduced ones (Ch. 5 D's 1 km), Chapter 4's comparison on a
non-rotating Earth, or follow from the ECI correction itself; the values the project computes
are pinned by the ledger's rows, not here. (The text's "largest error of 1.5 km" is not
reproduced, so it is no threshold: the ledger scores it.)"""

import numpy as np
import pytest

from harp_analysis.analyses import comparisons, rotating
from harp_analysis.engines import eci
from harp_analysis.foundation import earth
from harp_analysis.models.launch import baseline_chapter_4

AIRS = ("two_segment", "three_layer")  # eqs 2.1-2.2, and Appendix A's 3DOF listing


def _non_rotating_worst_km() -> float:
    """The largest MKS error at apogee of Chapter 4's comparison on a non-rotating Earth (the
    baseline over its elevations): the accuracy the ECI correction is to carry over."""
    return max(
        comparisons.error_at_apogee_km("baseline", e) for e in comparisons.BASELINE_ELEVATIONS_DEG
    )


@pytest.mark.parametrize("atmosphere", AIRS)
def test_most_errors_are_under_1km_and_the_higher_shots_within_the_non_rotating_worst(atmosphere):
    """Ch. 5 D: "for most of the trajectories, the total position error is less than 1 km".
    With the ECI correction the rotating Earth costs the higher elevations (45-85 deg) no
    accuracy beyond what the MKS has on a non-rotating Earth: within Chapter 4's worst."""
    errors = rotating.errors_at_apogee_km(atmosphere)
    assert np.mean(np.array(list(errors.values())) < 1.0) > 0.5
    assert max(v for (_, _, el), v in errors.items() if el >= 45.0) < _non_rotating_worst_km()


@pytest.mark.parametrize("atmosphere", AIRS)
def test_the_error_grows_for_lower_elevations(atmosphere):
    """Ch. 5 D: "the error grows for lower elevations": every 30 deg shot is worse than the
    45 deg shot on the same bearing from the same latitude."""
    errors = rotating.errors_at_apogee_km(atmosphere)
    for lat in rotating.LATITUDES_DEG:
        for brg in rotating.BEARINGS_DEG:
            assert errors[lat, brg, 30.0] > errors[lat, brg, 45.0], (lat, brg)


def test_appendix_a_air_puts_the_worst_case_where_the_text_does():
    """Ch. 5 D: the worst case of the higher elevations is 270T, 45 deg, from the equator. In
    Appendix A's three-layer air (its 3DOF listing) the comparison finds it there."""
    assert rotating.worst_case(45.0, atmosphere="three_layer") == (0.0, 270.0, 45.0)


@pytest.mark.parametrize("bearing", [90.0, 270.0])
def test_printed_decay_is_worse_than_anything_the_text_reports(bearing):
    """Eq 6.14 as printed drops (Vrel/V)^2 from the decay: east and west at 45 deg it puts the
    error beyond the worst of the non-rotating comparison (Chapter 4), while the consistent
    decay stays within it."""
    consistent = rotating.error_at_apogee_km(0.0, bearing, 45.0)
    printed = rotating.error_at_apogee_km(0.0, bearing, 45.0, decay="printed")
    assert consistent < _non_rotating_worst_km() < printed


@pytest.mark.parametrize(
    "latitude, bearing, elevation",
    [(45.0, 0.0, 65.0), (0.0, 90.0, 45.0), (0.0, 270.0, 45.0), (0.0, 0.0, 30.0)],
)
def test_mks_leaves_the_3dof_at_the_tangent_speed(latitude, bearing, elevation):
    """Both start at the gun; the MKS's launch velocity is the 3DOF's, Vrel + omega x r0, plus
    V_tangent (eq 6.15) normal to it. So the distance between them grows at |V_tangent|
    (eq 5.8) at first: error/t extrapolated to t = 0 from the first two rows (0.5 and 1 s)
    equals it, to the curvature of error/t over that second (under 1 %)."""
    _, _, errors = rotating.case(latitude, bearing, elevation)
    t, error = errors.time_s.to_numpy()[1:3], errors.error_m.to_numpy()[1:3]
    assert t == pytest.approx([0.5, 1.0])
    rate_at_launch = 2 * error[0] / t[0] - error[1] / t[1]
    launch = baseline_chapter_4(
        elevation,
        latitude_deg=latitude,
        bearing_deg=bearing,
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
    )
    tangent = float(eci.correction_for_launch(launch).tangent_speed_m_s)
    assert rate_at_launch == pytest.approx(tangent, rel=0.01)


def test_the_air_is_the_launch_air():
    """The three-layer case flies the three-layer 3DOF (and is a different flight)."""
    two, _, _ = rotating.case(0.0, 90.0, 45.0)
    three, _, _ = rotating.case(0.0, 90.0, 45.0, atmosphere="three_layer")
    assert two.attrs["launch"].atmosphere == "two_segment"
    assert three.attrs["launch"].atmosphere == "three_layer"
    assert two.attrs["apogee_altitude_m"] != three.attrs["apogee_altitude_m"]


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="latitude_deg"):
        rotating.case(95.0, 90.0, 45.0)
    with pytest.raises(ValueError, match="bearing_deg"):
        rotating.case(0.0, 360.0, 45.0)
    with pytest.raises(ValueError, match="decay"):
        rotating.case(0.0, 90.0, 45.0, decay="exact")
    with pytest.raises(ValueError, match="atmosphere"):
        rotating.case(0.0, 90.0, 45.0, atmosphere="martian")
