"""Compiled kernels: one source for numpy and numba, the same numbers from both, and a disk cache
that a change to any formula a kernel reaches invalidates."""

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from harp_analysis.analyses import effort
from harp_analysis.engines import threedof
from harp_analysis.foundation import compiled, kernel_digest, validation
from harp_analysis.models import atmosphere, drag
from harp_analysis.models.launch import HP_CHAPTER_2, baseline_chapter_4

ALTITUDES_M = st.floats(min_value=0.0, max_value=99_000.0)


@settings(max_examples=60, deadline=None)
@given(altitude_m=ALTITUDES_M)
def test_compiled_air_is_the_numpy_formulas(altitude_m):
    """Every model's compiled density and speed of sound equal its numpy formulas (libm's exp
    and pow may differ from numpy's in the last bit)."""
    for name in atmosphere.ATMOSPHERE_NAMES:
        model = atmosphere.get_atmosphere(name)
        density, sound = atmosphere.air(model.code, altitude_m, model.table())
        assert density == pytest.approx(float(model.density_kernel(np.array(altitude_m))), 1e-14)
        assert sound == pytest.approx(float(model.sound_kernel(np.array(altitude_m))), rel=1e-14)


@settings(max_examples=60, deadline=None)
@given(mach=st.floats(min_value=0.0, max_value=10.0))
def test_compiled_drag_coefficient_is_the_law(mach):
    for law in (drag.BASELINE_CONE, drag.M829.zero_yaw_drag()):
        code, *tables = law.kernel_parameters()
        assert drag.drag_coefficient(code, mach, *tables) == pytest.approx(
            float(law.evaluate(mach)), rel=1e-14
        )


def test_select_is_where_on_arrays_and_a_choice_on_numbers():
    assert np.array_equal(compiled.select(np.array([True, False]), 1.0, 2.0), [1.0, 2.0])
    choose = compiled.jit(lambda flag: compiled.select(flag, 1.0, 2.0))
    assert choose(True) == 1.0 and choose(False) == 2.0
    assert isinstance(choose(True), float)  # a number, not numba's 0-d array of np.where


@settings(max_examples=200, deadline=None)
@given(
    value=st.floats(allow_nan=True, allow_infinity=True),
    ends=st.sampled_from([(0.0, 1.0), (-2.5, 0.0), (0.0, math.inf), (-math.inf, math.inf)]),
    flags=st.tuples(st.booleans(), st.booleans()),
)
@example(value=math.inf, ends=(0.0, math.inf), flags=(True, True))
@example(value=-math.inf, ends=(-math.inf, math.inf), flags=(True, True))
@example(value=math.nan, ends=(-math.inf, math.inf), flags=(True, True))
@example(value=1.0, ends=(0.0, 1.0), flags=(True, False))
def test_an_interval_holds_the_same_numbers_compiled_as_in_python(value, ends, flags):
    """Bounds' one test of membership, written out here: an end is reached only where closed,
    and NaN and infinities lie in no interval (a kernel and a door must not disagree)."""
    (low, high), (low_closed, high_closed) = ends, flags
    expected = (
        math.isfinite(value)
        and (low <= value if low_closed else low < value)
        and (value <= high if high_closed else value < high)
    )
    bounds = validation.Bounds(low, high, low_closed, high_closed)
    kernel = compiled.jit(lambda x: validation.inside(x, low, high, low_closed, high_closed))
    assert bool(bounds.inside(value)) is expected
    with np.errstate(invalid="ignore"):  # inf - inf, the finite test, is NaN by design
        assert bool(bounds.inside(np.array([value]))[0]) is expected
    assert kernel(value) is expected


def test_the_cache_folder_follows_every_formula_a_kernel_reaches():
    """numba alone would keep a kernel compiled against an old formula of another module."""
    sources = {path.name for path in kernel_digest._sources("harp_analysis.engines.threedof")}
    assert {"threedof.py", "integrator.py", "atmosphere.py", "drag.py", "compiled.py"} <= sources
    assert "effort.py" not in sources  # an analysis the engine does not reach


def test_a_vector_counts_once_as_numpy_s_does():
    def per_component(x, y):
        return compiled.vector(x[0] - y[0] * 2.0, x[1] - y[1], x[2])

    def numpy_vector(x, y):
        return x - y * 2.0

    assert effort.count_flops(per_component) == effort.count_flops(numpy_vector) == 2


@pytest.mark.parametrize("launch", [baseline_chapter_4(45.0), HP_CHAPTER_2])
def test_batch_and_single_flight_are_the_same_integration(launch):
    """fly_3dof (a batch's kernel) and simulate_3dof (one flight with its table) run the same
    compiled integration: the same steps, evaluations, apogee and impact."""
    table = threedof.simulate_3dof(launch).attrs
    flights = threedof.fly_3dof([launch, launch.but(elevation_deg=70.0), launch])
    for i in (0, 2):
        assert flights.steps[i] == table["steps"]
        assert flights.rhs_evaluations[i] == table["rhs_evaluations"]
        assert flights.apogee_altitude_m[i] == pytest.approx(table["apogee_altitude_m"], 1e-12)
        assert flights.range_m[i] == pytest.approx(table["range_m"], rel=1e-12)
        assert flights.time_of_flight_s[i] == pytest.approx(table["time_of_flight_s"], 1e-12)


def test_a_module_imported_for_a_constant_counts_in_the_digest():
    """trajectory.py takes only a number from earth.py, which numba bakes into machine code."""
    from pathlib import Path

    from harp_analysis.models import trajectory

    assert "earth.py" in {path.name for path in kernel_digest._imported(Path(trajectory.__file__))}


def test_unknown_model_numbers_are_refused_in_compiled_code():
    with pytest.raises(ValueError, match="unknown atmosphere code"):
        atmosphere.air(99, 1000.0, np.zeros((3, 2)))
    with pytest.raises(ValueError, match="unknown drag law code"):
        drag.drag_coefficient(99, 2.0, np.zeros(3), np.zeros(2), np.zeros(2))


def test_a_flight_that_cannot_be_integrated_raises_instead_of_looping():
    batch = threedof._batch([baseline_chapter_4(45.0)])
    poisoned = batch._replace(columns=np.full_like(batch.columns, np.nan))
    with pytest.raises(FloatingPointError, match="could not integrate launch 0"):
        threedof._fly(poisoned, 3000.0, 1e-9, record=False)


KERNEL_MODULE = """
from harp_analysis.foundation.compiled import jit


@jit
def polynomial(x):
    total = x
    for power in range(2, 12):
        total += x**power / power
    return total
"""
# compiles (or loads) the kernel once the test says go; prints how many signatures it compiled
COMPILE_AT_GO = """
import pathlib, sys, time
import kernel_module
ready, go = map(pathlib.Path, sys.argv[1:])
ready.touch()
while not go.exists():
    time.sleep(0.005)
assert kernel_module.polynomial(2.0) == kernel_module.polynomial.py_func(2.0)
print(sum(kernel_module.polynomial.stats.cache_misses.values()))
"""


def test_processes_compiling_a_kernel_at_once_compile_it_once(tmp_path):
    """Two processes compile one kernel into an empty cache at once (two notebooks opened after
    an upgrade): both succeed, one compiles and the other loads what it saved, and a third
    process loads it without compiling. Unguarded, both compile and both rewrite numba's index."""
    import os
    import subprocess
    import sys
    import time

    (tmp_path / "kernel_module.py").write_text(KERNEL_MODULE)
    go = tmp_path / "go"
    env = {
        **os.environ,
        "HARP_ANALYSIS_KERNEL_CACHE": str(tmp_path / "cache"),
        "PYTHONPATH": str(tmp_path),
    }

    def start(name: str) -> subprocess.Popen:
        command = [sys.executable, "-c", COMPILE_AT_GO, str(tmp_path / name), str(go)]
        return subprocess.Popen(command, env=env, stdout=subprocess.PIPE, text=True)

    pair = [start("ready0"), start("ready1")]
    while not all((tmp_path / f"ready{i}").exists() for i in range(2)):
        assert all(process.poll() is None for process in pair), "a process failed to start"
        time.sleep(0.005)
    go.touch()  # both are imported and waiting: they reach the empty cache together
    compiled = sorted(int(process.communicate(timeout=300)[0]) for process in pair)
    assert [process.returncode for process in pair] == [0, 0]
    assert compiled == [0, 1]
    third = start("ready2")
    assert int(third.communicate(timeout=300)[0]) == 0 and third.returncode == 0


PART_MODULE = """
from harp_analysis.foundation.compiled import jit


@jit(cache=False)
def part(x, power):
    return x**power


@jit
def kernel(x):
    return part(x, 3) + part(x, 2)
"""
# calls the kernel; prints the kernel's signatures loaded and compiled and the part's compiled
CALL_KERNEL = """
import kernel_parts
assert kernel_parts.kernel(2.0) == 12.0
print(sum(kernel_parts.kernel.stats.cache_hits.values()),
      sum(kernel_parts.kernel.stats.cache_misses.values()), len(kernel_parts.part.signatures))
"""


def _fresh_python(code: str, cache, path, cwd=None) -> str:
    """What ``code`` prints in a fresh, compiling interpreter (``NUMBA_DISABLE_JIT`` dropped)
    that imports from ``path`` and keeps its kernels in ``cache``."""
    import os
    import subprocess
    import sys

    env = {**os.environ, "HARP_ANALYSIS_KERNEL_CACHE": str(cache), "PYTHONPATH": str(path)}
    env.pop("NUMBA_DISABLE_JIT", None)
    run = subprocess.run(
        [sys.executable, "-c", code],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert run.returncode == 0, run.stderr
    return run.stdout


def test_a_part_kept_in_memory_is_cached_within_its_kernel(tmp_path):
    """A function compiled only within cached kernels (``jit(cache=False)``, the 3DOF's
    integrator) writes no cache file and takes no lock of its own, so that processes compiling
    different kernels do not wait for one another; a fresh process loads the kernel whole,
    compiling neither it nor the part."""
    (tmp_path / "kernel_parts.py").write_text(PART_MODULE)
    cache = tmp_path / "cache"

    def call() -> list[int]:
        return [int(word) for word in _fresh_python(CALL_KERNEL, cache, tmp_path).split()]

    assert call() == [0, 1, 2]  # compiled: the kernel once, the part for each literal power
    names = {path.name for path in cache.rglob("*") if path.is_file()}
    assert any(name.startswith("kernel_parts.kernel") for name in names)
    assert not any("part-" in name or ".part" in name for name in names), names
    assert call() == [1, 0, 0]  # loaded whole: the part's machine code is in the kernel's file


# warms one engine up (flight_grid's: its one kernel is the cheapest to compile) and prints the
# package's file and how many signatures every kernel of the package loaded and compiled
WARM_UP_AND_COUNT = """
import json, sys
from numba.core.dispatcher import Dispatcher
import harp_analysis
from harp_analysis.engines import flight_grid
flight_grid.warm_up()
kernels = {id(value): value for name, module in list(sys.modules.items())
           if name.startswith("harp_analysis") for value in vars(module).values()
           if isinstance(value, Dispatcher)}.values()
print(json.dumps({"package": harp_analysis.__file__,
                  "hits": sum(sum(k.stats.cache_hits.values()) for k in kernels),
                  "misses": sum(sum(k.stats.cache_misses.values()) for k in kernels)}))
"""


def test_a_second_checkout_loads_what_the_first_compiled(tmp_path):
    """Two copies of the package's sources at different paths, their files written at different
    times (two clones, a worktree, a CI run): an engine warmed up in the first compiles its
    kernels into the user's cache, and the second loads them, compiling nothing and adding or
    rewriting no file there. numba's own cache, kept by each file's location, would compile
    them again."""
    import json
    import os
    import shutil
    import time
    from pathlib import Path

    cache = tmp_path / "kernels"
    now = time.time()

    def checkout(name: str, written: float) -> Path:
        root = tmp_path / name
        ignore = shutil.ignore_patterns("__pycache__")
        shutil.copytree(Path(compiled.__file__).parents[1], root / "harp_analysis", ignore=ignore)
        for path in root.rglob("*"):
            os.utime(path, (written, written))
        return root

    def warm_up(root: Path) -> dict:
        printed = _fresh_python(WARM_UP_AND_COUNT, cache, root, cwd=root)
        counts = json.loads(printed.splitlines()[-1])
        assert counts["package"] == str(root / "harp_analysis" / "__init__.py")  # the copy's
        return counts

    def kept() -> dict:  # numba's index and data files, as written
        return {
            path: (path.stat().st_size, path.stat().st_mtime_ns)
            for path in cache.rglob("*")
            if path.suffix in (".nbi", ".nbc")
        }

    first = checkout("first", now)
    second = checkout("second", now - 400 * 86400)
    compiled_first = warm_up(first)
    assert compiled_first["misses"] > 0 and compiled_first["hits"] == 0  # an empty cache
    saved = kept()
    assert saved
    loaded = warm_up(second)
    assert loaded["misses"] == 0, "the second checkout compiled kernels the first had saved"
    assert loaded["hits"] > 0
    assert kept() == saved


# the Chapter 4 baseline's drag coefficient at Mach 2.25 (a kernel of models.drag, cheap to
# compile), and how many signatures the package's kernels and the test's loaded and compiled
DRAG_AND_COUNT = """
import json
import kernel_module
from harp_analysis.models import drag
code, *tables = drag.BASELINE_CONE.kernel_parameters()
kernels = [drag.drag_coefficient, kernel_module.polynomial]
print(json.dumps({"cd": drag.drag_coefficient(code, 2.25, *tables),
                  "polynomial": kernel_module.polynomial(2.0),
                  "hits": sum(sum(k.stats.cache_hits.values()) for k in kernels),
                  "misses": sum(sum(k.stats.cache_misses.values()) for k in kernels)}))
"""


def test_with_the_numba_cache_hooks_off_kernels_compile_in_every_process(tmp_path):
    """``HARP_ANALYSIS_NUMBA_CACHE=0`` leaves numba's dispatcher as njit makes it: the same
    numbers (the drag law of eq 4.8 at Mach 2.25, a polynomial against Python's), compiled again
    by a second process (slower) and nothing written to the kernels' folder."""
    import json
    import math
    import os

    from harp_analysis.foundation import numba_cache

    (tmp_path / "kernel_module.py").write_text(KERNEL_MODULE)
    cache = tmp_path / "kernels"
    os.environ[numba_cache.SWITCH] = "0"  # inherited by the fresh interpreters below
    try:
        runs = [json.loads(_fresh_python(DRAG_AND_COUNT, cache, tmp_path)) for _ in range(2)]
    finally:
        del os.environ[numba_cache.SWITCH]
    law = 0.077 * math.exp(-0.38 * 2.25) + 0.014  # eq 4.8, written out
    polynomial = 2.0 + sum(2.0**power / power for power in range(2, 12))
    for run in runs:
        assert run["cd"] == pytest.approx(law, rel=1e-12)
        assert run["polynomial"] == pytest.approx(polynomial, rel=1e-15)
        assert run["misses"] == 2 and run["hits"] == 0  # each process compiled both
    assert not cache.exists() or not any(cache.rglob("*.nb*"))


def test_the_kernels_folder_follows_the_toolchain_not_where_the_files_are(monkeypatch, tmp_path):
    """The folder's name digests the compiler's versions (another numba, llvmlite, Python or
    CPU compiles afresh); HARP_ANALYSIS_KERNEL_CACHE moves it, else it is the user's."""
    import sys

    import llvmlite
    import numba
    from numba.core.registry import cpu_target

    toolchain = kernel_digest._toolchain()
    cpu = cpu_target.target_context.codegen()._get_host_cpu_name()
    for version in (numba.__version__, llvmlite.__version__, sys.version, cpu):
        assert version in toolchain
    monkeypatch.setenv("HARP_ANALYSIS_KERNEL_CACHE", str(tmp_path / "kernels"))
    folder = kernel_digest.cache_folder("harp_analysis.engines.mks")
    assert folder.parent == tmp_path / "kernels"
    assert kernel_digest.cache_folder("harp_analysis.engines.mks") == folder
    assert kernel_digest.cache_folder("harp_analysis.engines.flight_grid") != folder
    monkeypatch.setattr(kernel_digest, "_toolchain", lambda: toolchain + " another numba")
    assert kernel_digest.cache_folder("harp_analysis.engines.mks") != folder
    monkeypatch.delenv("HARP_ANALYSIS_KERNEL_CACHE")
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "user"))
    assert kernel_digest.cache_root() == tmp_path / "user" / "harp-analysis" / "kernels"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert kernel_digest.cache_root() == tmp_path / "home" / ".cache" / "harp-analysis" / "kernels"


def test_numba_s_debugging_switch_runs_the_same_physics_in_python():
    """NUMBA_DISABLE_JIT=1 (numba's switch for stepping through kernels in a debugger) leaves
    every kernel a Python function: the engines import and fly the same numbers."""
    import json
    import os
    import subprocess
    import sys

    from harp_analysis.engines import mks

    script = (
        "import json; from harp_analysis.analyses.fire_control import solver; "
        "from harp_analysis.engines import catalogue, mks, mks_improved, mlt, sixdof, threedof; "
        "from harp_analysis.models.launch import baseline_chapter_4 as b; "
        "print(json.dumps([mks.simulate_mks(b(45.0)).attrs['apogee_altitude_m'], "
        "float(threedof.fly_3dof([b(45.0)]).apogee_altitude_m[0])]))"
    )
    run = subprocess.run(
        [sys.executable, "-c", script],
        env={**os.environ, "NUMBA_DISABLE_JIT": "1"},
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert run.returncode == 0, run.stderr
    in_python, flown_in_python = json.loads(run.stdout)
    assert in_python == pytest.approx(
        mks.simulate_mks(baseline_chapter_4(45.0)).attrs["apogee_altitude_m"], rel=1e-12
    )
    compiled_3dof = threedof.fly_3dof([baseline_chapter_4(45.0)]).apogee_altitude_m[0]
    assert flown_in_python == pytest.approx(compiled_3dof, rel=1e-9)


def test_relative_imports_resolve_from_the_importing_file_s_own_folder(tmp_path):
    """In a subpackage, ``from ..models import drag`` names a file two folders up from the
    importer, not one beside the package root: resolved against the root, the digest would drop
    it, and an edit to it would leave stale machine code in use (shared/design/LAYOUT.md)."""
    from pathlib import Path

    (tmp_path / "models").mkdir()
    (tmp_path / "engines").mkdir()
    for init in ("__init__.py", "models/__init__.py", "engines/__init__.py"):
        (tmp_path / init).write_text("")
    (tmp_path / "models" / "drag.py").write_text("CD = 0.3\n")
    (tmp_path / "models" / "air.py").write_text("RHO = 1.2\n")
    (tmp_path / "engines" / "fly.py").write_text(
        "from ..models import drag\nfrom ..models.air import RHO\nfrom . import helper\n"
    )
    (tmp_path / "engines" / "helper.py").write_text("")
    found = kernel_digest._imported(Path(tmp_path / "engines" / "fly.py"))
    assert found == {
        tmp_path / "models" / "drag.py",
        tmp_path / "models" / "air.py",
        tmp_path / "models" / "__init__.py",
        tmp_path / "engines" / "helper.py",
    }


def _inverse(x):
    return 1.0 / x


def test_zero_division_follows_python_unless_asked_for_ieee():
    """A kernel's ``/`` by zero raises as Python's does, or gives inf as numpy's does when
    compiled with zero_division="ieee"; any other choice is refused by name."""
    with pytest.raises(ZeroDivisionError):
        compiled.jit(_inverse, cache=False)(0.0)
    assert compiled.jit(_inverse, cache=False, zero_division="ieee")(0.0) == np.inf
    assert compiled.jit(_inverse, cache=False, zero_division="ieee")(-0.0) == -np.inf
    with pytest.raises(ValueError, match="zero_division"):
        compiled.jit(_inverse, zero_division="numpy")
