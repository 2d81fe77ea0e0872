"""Every benchmark (each ``benchmarks/bench_*.py``) in its smoke mode (tiny sizes, one round, no
cold start): each path runs and each reference agrees with the package to its stated accuracy
(the benchmarks raise if not), so that no benchmark rots unseen. Timings are printed, never
asserted."""

import importlib
import sys
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"
NAMES = sorted(path.stem for path in BENCHMARKS.glob("bench_*.py"))
# A line each benchmark's output must hold (its last table or verdict), where one is known.
EXPECTED = {
    "bench_atmosphere": "two_segment",
    "bench_threedof": "target: engine (fly_3dof) within 1.5x of the lean reference",
    "bench_sixdof": "right-hand side",
    "bench_mlt": "MLT segment (m)",
    "bench_mks": "target (computing beta and tau): class, first zero",
    "bench_fire_control": "Reference, one converged 3DOF intercept",
    "bench_sweeps": "same apogees",  # its smoke clusters are threads of this process
    "bench_figures": "PNG byte-identical to the reference's",
    "bench_mks_improved": "target: a solve in 5 ms",
    "bench_calibrated_mks": "launches at once",
}


def test_every_listed_benchmark_exists():
    assert set(EXPECTED) <= set(NAMES)


@pytest.mark.parametrize("name", NAMES)
def test_benchmark_smoke(monkeypatch, capsys, name):
    monkeypatch.syspath_prepend(str(BENCHMARKS))  # as its own script sees its folder
    monkeypatch.setattr(sys, "argv", [sys.argv[0]])
    importlib.import_module(name).main(smoke=True)
    output = capsys.readouterr().out
    assert EXPECTED.get(name, "\n") in output
