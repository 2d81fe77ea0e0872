"""Shared results cannot be corrupted by a caller: every cache of the package is either
:func:`harp_analysis.foundation.caching.cached_copies` (each caller its own deep copy) or a plain
cache of a result nobody can edit, listed here with the reason. A new bare cache fails the scan
until it is one or the other."""

import ast
import copy
import dataclasses
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import harp_analysis
from harp_analysis.analyses import effort, error_budget, mks_improvement, scenarios
from harp_analysis.analyses.harp import apogees, confidence, identification
from harp_analysis.foundation import caching
from harp_analysis.models.launch import HP_CHAPTER_2
from harp_analysis.reporting import ledger, registry

PACKAGE = Path(harp_analysis.__file__).parent

#: Plain caches whose results cannot be edited: module.function -> what it returns.
IMMUTABLE_RESULTS = {
    "foundation.kernel_digest._imported_as_of": "a frozenset of paths",
    "foundation.kernel_digest._digest": "a string",
    "foundation.kernel_digest._toolchain": "a string",
    "reporting.explorer._typical_martlet_mass_kg": "a float",
    "analyses.fire_control.studies.costs.raid_against_3dof_intercept": "a frozen RaidComparison",
    "analyses.fire_control.studies.model_comparison.calibrated_fire_control": (
        "a frozen CalibratedFireControl of numbers"
    ),
    "analyses.fire_control.verification.clearance": "a float (one branch search's)",
    "analyses.fire_control.verification.shoot": "a _Shot of numbers (one branch search's)",
    "analyses.harp.apogees.fit_drag_area_to_errors": "a tuple of three floats",
    "analyses.harp.apogees._drag_area_m2": "a float",
    "analyses.mks_improvement.calibration": "a frozen Calibration of one float",
    "reporting.registry.load_registry": "a tuple of frozen RegistryEntry of strings and a bool",
    "models.taylor_maccoll.baseline_fit": "a frozen DragFit of four floats",
    "engines.threedof._kernels": "a tuple of compiled functions",
    "engines.calibrated_mks._calibration": "a frozen Calibration whose arrays are read-only",
    "engines.flyout_table._table": "a frozen FlyoutTable whose arrays are read-only",
}

#: Plain caches in other engineers' modules that hand out editable objects (issue 25, item 4:
#: reported for them to convert); each leaves this list when it becomes cached_copies or is
#: shown immutable.
NOT_YET_COPIES = {
    "models.atmosphere._standard_table": "a tuple of numpy arrays (private, read by the kernels)",
    "engines.mks._gauss_legendre": "a tuple of numpy arrays (nodes and weights)",
    "reporting.save_shortcuts.subset_font": "bytes and a dict of glyph indices",
    "models.rigid_body._model": "the RigidBodyModel the 6DOF and MLT flights of a projectile share",
    "engines.threedof._shared": "numpy arrays (the atmosphere's table, breakpoints)",
}

_CACHES = {"cache", "lru_cache", "cached_copies"}


def _decorator_name(node: ast.expr) -> str | None:
    if isinstance(node, ast.Call):
        node = node.func
    if isinstance(node, ast.Attribute):
        return node.attr
    return node.id if isinstance(node, ast.Name) else None


def package_caches() -> dict[str, str]:
    """Every cached function of the package, in every folder, module.function -> its
    decorator's name (the module dotted from the package, ``engines.mks``)."""
    found = {}
    for source in sorted(PACKAGE.rglob("*.py")):
        module = ".".join(source.relative_to(PACKAGE).with_suffix("").parts)
        for node in ast.walk(ast.parse(source.read_text())):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                for decorator in node.decorator_list:
                    name = _decorator_name(decorator)
                    if name in _CACHES:
                        found[f"{module}.{node.name}"] = name
    return found


CACHES = package_caches()


def test_every_bare_cache_returns_an_immutable_result_or_is_listed():
    bare = {name for name, decorator in CACHES.items() if decorator != "cached_copies"}
    unlisted = bare - set(IMMUTABLE_RESULTS) - set(NOT_YET_COPIES)
    assert not unlisted, (
        f"{sorted(unlisted)} cache a result without copying it: decorate with "
        "harp_analysis.foundation.caching.cached_copies, or, if the result cannot be edited "
        "(numbers, "
        "strings, tuples of them, frozen dataclasses of them), list it in IMMUTABLE_RESULTS"
    )


def test_the_lists_name_only_bare_caches_that_exist():
    """A cache converted or removed leaves the lists (they would hide the next one)."""
    for name in (*IMMUTABLE_RESULTS, *NOT_YET_COPIES):
        assert CACHES.get(name) in ("cache", "lru_cache"), name


@pytest.mark.parametrize(
    "function, args",
    [
        (apogees.fit_drag_area_to_errors, ()),
        (apogees.drag_area_m2, ("consistent",)),
        (mks_improvement.calibration, ()),
        (registry.load_registry, ()),
    ],
    ids=lambda value: getattr(value, "__name__", ""),
)
def test_listed_immutable_results_are_hashable(function, args):
    """Hashable all the way down: no array, frame, list or dict inside."""
    hash(function(*args))


def _edit(value, seen=None) -> None:
    """Overwrite everything editable in ``value``, recursively."""
    seen = set() if seen is None else seen
    if id(value) in seen:
        return
    seen.add(id(value))
    if isinstance(value, np.ndarray):
        if value.flags.writeable and value.dtype.kind in "fc":
            value[...] = np.nan
    elif isinstance(value, pd.DataFrame):
        for column in value.columns:
            if value[column].dtype.kind in "iuf":
                value[column] = -1
        value.attrs.clear()
    elif isinstance(value, pd.Series):
        if value.dtype.kind in "iuf":
            value.iloc[:] = -1
        value.attrs.clear()
    elif isinstance(value, dict):
        value.clear()
    elif isinstance(value, list):
        value.clear()
    elif isinstance(value, tuple):
        for item in value:
            _edit(item, seen)
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        for field in dataclasses.fields(value):
            _edit(getattr(value, field.name), seen)


def _same(a, b) -> bool:
    if isinstance(a, pd.DataFrame | pd.Series):
        return a.equals(b) and a.attrs.keys() == b.attrs.keys()
    if isinstance(a, np.ndarray):
        return np.array_equal(a, b, equal_nan=True)
    if isinstance(a, tuple | list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return a == b


@pytest.mark.parametrize(
    "function, args",
    [
        (error_budget.nominal, (error_budget.representative_launches()["baseline, 45 deg"],)),
        (apogees.appendix_rounds, ("barbados",)),
        (apogees.predicted_apogees, ("yuma",)),
        (confidence._rounds, ("yuma",)),
        (identification.identification_table, ()),
        (ledger.load_claims, ()),
        (effort._mlt_costs, (HP_CHAPTER_2,)),
        (mks_improvement._flight, (HP_CHAPTER_2.but(cross_wind_m_s=0.0),)),
        (scenarios.fly_3dof, (HP_CHAPTER_2,)),
    ],
    ids=lambda value: getattr(value, "__name__", ""),
)
def test_editing_a_cached_result_changes_no_later_call(function, args):
    first = function(*args)
    pristine = copy.deepcopy(first)
    _edit(first)
    assert _same(function(*args), pristine)


def test_an_unhashable_argument_is_named():
    @caching.cached_copies
    def total(values, scale=1.0):
        return sum(values) * scale

    assert total((1, 2), scale=2.0) == 6.0
    with pytest.raises(TypeError, match="total: values must be hashable .*a tuple, not a list"):
        total([1, 2])
    with pytest.raises(TypeError, match="total: scale must be hashable"):
        total((1, 2), scale={})
