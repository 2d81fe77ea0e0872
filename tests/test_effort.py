"""The operation counter follows its stated rule (operators, loops, branches, complex weight),
the counted MKS code is the MKS, and MLT is counted call by call as it runs."""

import functools
import importlib
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import DOP853

import harp_analysis
from harp_analysis.analyses import effort
from harp_analysis.engines import mks, mlt
from harp_analysis.models import atmosphere, rigid_body
from harp_analysis.models.launch import HP_CHAPTER_2, Launch
from harp_analysis.models.projectiles import BASELINE, HP


def _sample(x, y):
    """Two multiplies, two adds, a square (1), a sqrt (1) and an exp (10): 16."""
    return np.exp(x * y + x * x) + np.sqrt(y**2)


def test_counting_rule():
    assert effort.count_flops(_sample) == 2 + 2 + 1 + 1 + 10


def test_dop853_overhead_grows_with_states():
    """Per state, from scipy's published DOP853 tableau (not the module's constants): a
    multiply-add (2) per coefficient of each stage's dense combination of the earlier stages,
    of the solution weights and of the two error estimators, and 4 for the error norm."""
    stages = DOP853.n_stages
    per_state = (
        sum(2 * s for s in range(1, stages))
        + 2 * len(DOP853.B)
        + 2 * len(DOP853.E3)
        + 2 * len(DOP853.E5)
        + 4
    )
    assert effort.dop853_step_flops(12) - effort.dop853_step_flops(6) == 6 * per_state


@pytest.mark.parametrize("projectile, elevation", [(BASELINE, 45.0), (BASELINE, 85.0), (HP, 50.0)])
def test_counted_mks_apogee_is_the_mks(projectile, elevation):
    """The counted straight-line code gives the MKS's apogee, fed from outside the MKS: Cd0
    from the drag law at the launch Mach number in the launch's air (eqs 2.1-2.2), rho0 of eq
    3.11; and the MKS's beta is eq 3.22 with the text's k = 0.117 /km."""
    launch = Launch(projectile, projectile.launch_speed_m_s, elevation)
    solution = mks.for_launch(launch, warn=False)
    sound = atmosphere.get_atmosphere("two_segment").speed_of_sound(0.0)
    cd0 = float(projectile.drag_law(projectile.launch_speed_m_s / sound))
    rho0, k = 1.225, 0.117e-3  # eq 3.11
    phi = np.radians(elevation)
    beta = cd0 * rho0 * projectile.reference_area_m2 / (2 * k * projectile.mass_kg * np.sin(phi))
    assert solution.beta.item() == pytest.approx(beta, rel=1e-12)  # eq 3.22
    apogee = effort.mks_apogee(
        projectile.launch_speed_m_s,
        phi,
        cd0,
        projectile.mass_kg,
        projectile.reference_area_m2,
        rho0=rho0,
    )
    assert apogee == pytest.approx(solution.apogee_altitude("eq_6_4"), rel=1e-9)


_TABLE = (1.0, 2.0, 3.0, 4.0)


def _loops(x, items):
    """A 3-trip range loop of 2 operations (6), a generator over the module's 4-item _TABLE
    (1 each) and the add of its sum (5), and a loop over ``items`` of 1 operation (5 trips when
    the caller says so): 16."""
    total = 0.0
    for i in range(3):
        total = total + x * i
    total = total + sum(c * x for c in _TABLE)
    for item in items:
        total = total - item
    return total


def _branches(x):
    """The test (1), then the costlier of the early return (2) and the rest: an add (1) and
    the costlier branch of the conditional expression (3, not 1): 5."""
    if x > 0:
        return x * x * x
    y = x + 1
    return y * y + y / 2 if y else -y


def _nested(x):
    """A nested function of 2 operations called twice (4), the square and the add: 6."""

    def twice(v):
        return 2 * v + 1

    return twice(x) + twice(x * x)


def test_loops_count_once_per_item():
    assert effort.count_flops(_loops, trips={"items": 5}) == 6 + 5 + 5
    with pytest.raises(ValueError, match="'items' of unknown length"):
        effort.count_flops(_loops)


def test_branches_count_along_the_costliest_path():
    assert effort.count_flops(_branches) == 5


def test_nested_functions_count_per_call():
    assert effort.count_flops(_nested) == 6


def test_complex_weight_multiplies_every_operation():
    assert effort.count_flops(_sample, weight=effort.COMPLEX_WEIGHT) == 4 * 16
    costs = effort._mlt_costs(HP_CHAPTER_2)
    in_complex = [c.function for c in mlt.counted_functions(HP_CHAPTER_2) if c.complex_numbers]
    assert in_complex == [mlt._phi, mlt._epicyclic_solution]
    for function in in_complex:
        assert costs[function.__code__] == effort.COMPLEX_WEIGHT * effort.count_flops(function)
    # _phi along its costlier path: |z| > 1 (2), the series' multiply-add per term, its last
    # three steps (6); the exponential branch (16 operations) is the cheaper one.
    assert costs[mlt._phi.__code__] == 4 * (2 + 2 * len(mlt._PHI3_SERIES) + 6)


def test_sixdof_coefficients_are_counted_for_every_table_column():
    """The counted interpolation returns all nine coefficients of Appendix B's table."""
    model = rigid_body.rigid_body_model(
        HP, atmosphere.get_atmosphere("two_segment"), (0.0, 0.0, 0.0), "flat"
    )
    assert len(model.rows[0]) == len(model.slopes[0]) == 9
    assert len(rigid_body.RigidBodyModel.coefficients(model, 2.2)) == 9


#: Chapter 2 A's HP launch (50 deg, 2022 m/s, 5 m/s cross wind, 10 rad/s) and MLT's options.
_LAUNCH = HP_CHAPTER_2
_FLIGHT = dict(density_altitude="spherical")


def test_mlt_calls_per_segment():
    """Two coefficient evaluations and three propagations a segment, one more propagation per
    brentq evaluation, one for the apogee state and one for the impact state (checked for the
    pitch turned and an apogee inside the landing segment; the radial-velocity checks reuse
    states)."""
    calls, table = effort._mlt_run(_LAUNCH, **_FLIGHT)
    n = table.attrs["steps"]
    count = {code.co_qualname: k for code, k in calls.items() if code.co_filename == mlt.__file__}
    assert count["segment_coefficients"] == 2 * n
    assert count["_solve_segment"] == count["_Segment.duration_s"] == n
    brentq_evaluations = count.get(f"{mlt.SEGMENT_LOOP.__name__}.<locals>.<lambda>", 0)
    assert count["propagate_segment"] == 3 * n + brentq_evaluations + 2
    assert count["_phi"] >= 4 * count["propagate_segment"]
    assert n / 4 < count["_radial_velocity"] < 3 * n / 4  # the checks stop at the apogee


def test_mlt_counts_every_function_with_arithmetic():
    """Each function of the package that MLT's loop runs every segment is costed, runs inside
    a costed one (a generator, a nested function), is a diagnostic, or does no arithmetic."""
    calls, table = effort._mlt_run(_LAUNCH, **_FLIGHT)
    costs = effort._mlt_costs(_LAUNCH)
    costed = {code.co_qualname for code in costs}
    diagnostics = {function.__code__ for function in mlt.DIAGNOSTICS}
    package = Path(harp_analysis.__file__).parent
    checked = 0
    for code, k in calls.items():
        source = Path(code.co_filename)
        if code in costs or k < table.attrs["steps"] or not source.is_relative_to(package):
            continue
        if code.co_qualname.split(".<locals>.")[0] in costed - {code.co_qualname}:
            continue
        if code in diagnostics:
            continue
        if code.co_name in effort._SELECT:  # a primitive (compiled.select), counted where called
            continue
        module = ".".join(source.relative_to(package.parent).with_suffix("").parts)
        function = functools.reduce(
            getattr, code.co_qualname.split("."), importlib.import_module(module)
        )
        assert effort.count_flops(function) == 0, code.co_qualname
        checked += 1
    assert checked  # the functions of the package's subfolders are found (RigidBodyModel.air)


def test_mlt_count_scales_with_the_segments():
    coarse = effort.mlt_flops(_LAUNCH, segment_length_m=1000.0, **_FLIGHT)
    fine = effort.mlt_flops(_LAUNCH, segment_length_m=500.0, **_FLIGHT)
    assert fine / coarse == pytest.approx(2.0, rel=0.03)


def test_effort_table_rows():
    table = effort.effort_table()
    assert list(table.index[:4]) == ["6DOF", "3DOF", "MLT", "MKS (3 terms)"]
    assert table.flops["3DOF"] < table.flops["MLT"] < table.flops["6DOF"]
    # the counted MKS row flies the same launch as the MKS (its Cd0, rho0 of its air)
    mks_apogee = mks.for_launch(_LAUNCH, warn=False).apogee_altitude("eq_6_4")
    assert table.apogee_m["MKS (3 terms)"] == pytest.approx(mks_apogee, rel=1e-9)
    # Ch. 4 A: "four orders of magnitude decrease in computations over a 6DOF and three
    # orders of magnitude decrease over Modified Linear Theory and 3DOF simulations": at least
    # the smaller claim holds for every simulation (the ledger's ch4.effort rows score each)
    for method in ("6DOF", "3DOF", "MLT"):
        assert effort.orders_of_magnitude(method) >= 3.0, method
    # ``than`` compares any two rows: orders of magnitude add up
    assert effort.orders_of_magnitude("6DOF", than="3DOF") == pytest.approx(
        effort.orders_of_magnitude("6DOF") - effort.orders_of_magnitude("3DOF")
    )


def test_mlt_is_counted_in_the_two_segment_air_only():
    with pytest.raises(ValueError, match="two-segment"):
        effort.mlt_flops(_LAUNCH.but(atmosphere="three_layer"), **_FLIGHT)
