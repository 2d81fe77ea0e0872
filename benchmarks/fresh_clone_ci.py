"""A fresh clone's CI, timed (``make benchmark``; issue 36, item 5).

Clones this checkout's last commit into a folder beside it (as CI's checkout sits beside the
dissertation's text in ``../shared``, which the ledger's tests read) and runs its ``.ci/run``:
the README's test command, then the documentation site built and opened in the browser. The
user's kernel cache and pip's cache are used as CI finds them on this machine: the kernels of
sources compiled before are loaded, not compiled (``benchmarks/cold_compile.py`` measures
that), and the environment is installed from pip's cache. Uncommitted changes are not in the
clone. Printed: the wall time against the target of 6 minutes, and the CPU seconds; the run's
output is kept in ``build/fresh_clone_ci.log``.

Not a ``bench_*.py``: the documentation site runs those on every build, and this one takes
about ten minutes of both cores; ``make benchmark`` runs it last.
"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from measure import run_timed, verdict

TARGET_S = 360.0
ROOT = Path(__file__).resolve().parents[1]
LOG = ROOT / "build" / "fresh_clone_ci.log"


def _git(*arguments: str) -> str:
    return subprocess.run(
        ["git", *arguments], cwd=ROOT, check=True, capture_output=True, text=True
    ).stdout.strip()


def main() -> None:
    if "--smoke" in sys.argv[1:]:
        print("fresh clone's CI: not run in the smoke mode (ten minutes of both cores)")
        return
    commit = _git("rev-parse", "--short", "HEAD")
    if _git("status", "--porcelain", "--untracked-files=no"):
        print(f"fresh clone's CI: uncommitted changes are not measured, only {commit}")
    clone = ROOT.parent / f"{ROOT.name}-ci-{os.getpid()}"
    try:
        subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
        LOG.parent.mkdir(exist_ok=True)
        with LOG.open("wb") as log:
            run, wall, cpu = run_timed(
                [str(clone / ".ci" / "run")], cwd=clone, stdout=log, stderr=subprocess.STDOUT
            )
    finally:
        shutil.rmtree(clone, ignore_errors=True)
    if run.returncode:
        sys.stdout.buffer.write(LOG.read_bytes()[-4000:])
        raise SystemExit(f"fresh clone's CI failed on {commit} (exit {run.returncode}): {LOG}")
    minutes, seconds = divmod(round(wall), 60)
    print(
        f"fresh clone's CI: .ci/run on a clone of {commit}, {minutes} min {seconds} s "
        f"({cpu:.0f} s of CPU on {os.cpu_count()} cores); target {TARGET_S / 60:.0f} min: "
        f"{verdict(wall, TARGET_S)}"
    )


if __name__ == "__main__":
    main()
