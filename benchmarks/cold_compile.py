"""Every kernel ``make`` builds, compiled from an empty cache (``make benchmark``; issue 36).

Runs the Makefile's own kernel step (``make .venv/.kernels``, the environment taken as built)
with ``HARP_ANALYSIS_KERNEL_CACHE`` pointing at an empty folder, so that nothing is loaded: the
3DOF's atmosphere x drag-law pairs in one process per core beside one process compiling the
other engines, as a first ``make`` does. Printed: the wall time against the target of 60 s
(aim 30 s) on the quiet 2-core machine, and the CPU seconds of every process it ran.

Not a ``bench_*.py``: the documentation site runs those on every build, and this one costs a
minute of both cores; ``make benchmark`` runs it last.
"""

import os
import sys
import tempfile
from pathlib import Path

from measure import run_timed, verdict

TARGET_S, AIM_S = 60.0, 30.0
ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    if "--smoke" in sys.argv[1:]:
        print("cold compile: not run in the smoke mode (a minute of both cores)")
        return
    with tempfile.TemporaryDirectory() as empty:
        env = dict(os.environ, HARP_ANALYSIS_KERNEL_CACHE=empty)
        # -B remakes the kernel step; -o keeps the installed environment as it is
        command = ["make", "--no-print-directory", "-B", "-o", ".venv/.installed", ".venv/.kernels"]
        _, wall, cpu = run_timed(command, cwd=ROOT, env=env, check=True, capture_output=True)
        kernels = sum(1 for _ in Path(empty).rglob("*.nbi"))
    print(
        f"cold compile: make's kernel step into an empty cache, {kernels} compiled functions, "
        f"{wall:.0f} s ({cpu:.0f} s of CPU on {os.cpu_count()} cores); target {TARGET_S:.0f} s: "
        f"{verdict(wall, TARGET_S)}; aim {AIM_S:.0f} s: {verdict(wall, AIM_S)}"
    )


if __name__ == "__main__":
    main()
