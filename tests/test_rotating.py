"""Chapter 5's comparison: the ECI MKS tracks the rotating 3DOF, and the printed eq 6.14 does
not."""

import numpy as np
import pytest

from harp_analysis import rotating


def test_errors_at_apogee_stay_within_a_few_km():
    errors = [
        rotating.error_at_apogee_km(lat, brg, el)
        for lat in rotating.LATITUDES_DEG
        for brg in rotating.BEARINGS_DEG
        for el in rotating.ELEVATIONS_DEG
    ]
    assert max(errors) < 3.5 and np.median(errors) < 1.0


@pytest.mark.parametrize("bearing", [90.0, 270.0])
def test_printed_decay_is_worse_for_east_and_west(bearing):
    """Eq 6.14 as printed drops (Vrel/V)^2 from the decay: several km off east and west."""
    consistent = rotating.error_at_apogee_km(0.0, bearing, 45.0)
    printed = rotating.error_at_apogee_km(0.0, bearing, 45.0, decay="printed")
    assert printed > 3 * consistent


def test_errors_start_at_zero():
    _, _, errors = rotating.case(45.0, 0.0, 65.0)
    assert errors.error_m.iloc[0] < 1e-3


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="latitude_deg"):
        rotating.case(95.0, 90.0, 45.0)
    with pytest.raises(ValueError, match="bearing_deg"):
        rotating.case(0.0, 360.0, 45.0)
    with pytest.raises(ValueError, match="decay"):
        rotating.case(0.0, 90.0, 45.0, decay="exact")
