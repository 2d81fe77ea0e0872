"""The drag laws against the text's numbers, written out here: eq 4.8's fit of the baseline
cone and Appendix B's M829 zero-yaw drag, -CX0, as printed (issue 37, item 7: a slip in a
law's formula or table fails here, in its own module's tests)."""

import math

import numpy as np
import pytest

from harp_analysis.models.drag import BASELINE_CONE, get_drag_law

#: Appendix B's M829 table: Mach and CX0 as printed.
APPENDIX_B_MACH = (0.00, 1.00, 1.50, 2.00, 2.50, 3.00, 4.00, 5.00, 8.00)
APPENDIX_B_CX0 = (-0.60, -1.00, -1.35, -1.22, -1.04, -0.91, -0.69, -0.543, -0.449)


@pytest.mark.parametrize("mach", [0.0, 1.0, 3.0, 6.2, 10.0])
def test_the_baseline_cone_is_eq_4_8(mach):
    """Eq 4.8: Cd = 0.077 exp(-0.38 Ma) + 0.014."""
    assert BASELINE_CONE(mach) == pytest.approx(0.077 * math.exp(-0.38 * mach) + 0.014, rel=1e-15)
    assert get_drag_law("baseline_cone") is BASELINE_CONE


def test_the_m829_law_is_appendix_b_minus_cx0_at_its_nodes_and_linear_between():
    law = get_drag_law("m829")
    assert law(np.array(APPENDIX_B_MACH)) == pytest.approx([-c for c in APPENDIX_B_CX0], abs=0)
    middles = [(a + b) / 2 for a, b in zip(APPENDIX_B_MACH[:-1], APPENDIX_B_MACH[1:])]
    halfway = [-(a + b) / 2 for a, b in zip(APPENDIX_B_CX0[:-1], APPENDIX_B_CX0[1:])]
    assert law(np.array(middles)) == pytest.approx(halfway, rel=1e-14)


def test_the_m829_law_holds_its_last_value_beyond_mach_8():
    assert get_drag_law("m829")(np.array([9.0, 20.0])) == pytest.approx([0.449, 0.449], abs=0)
