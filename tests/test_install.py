"""The package works outside its checkout: a non-editable install into a fresh virtual
environment imports every submodule and loads the HARP tables from any directory."""

import shutil
import subprocess
import sys
import sysconfig
import venv
from pathlib import Path

import pytest

import harp_analysis

CHECKOUT = Path(__file__).resolve().parents[1]
SCRIPT = """
import importlib, pkgutil, sys
import harp_analysis
assert "site-packages" in harp_analysis.__file__, harp_analysis.__file__
names = [
    m.name for m in pkgutil.walk_packages(harp_analysis.__path__, "harp_analysis.")
    if not m.name.rpartition(".")[2].startswith("_")
]
for name in names:
    importlib.import_module(name)
from harp_analysis.analyses.harp import apogees, appendices
from harp_analysis.foundation import paths
assert len(appendices.load_barbados()) == 23 and len(appendices.load_yuma()) == 22
assert len(appendices.verify_checksums()) == 3
assert len(apogees.predicted_apogees("yuma")) == 22
try:
    paths.REGISTRY_DIR
except RuntimeError as error:
    assert "checkout" in str(error)
else:
    raise AssertionError("REGISTRY_DIR resolved without a checkout")
print(len(names), "submodules")
"""


@pytest.mark.skipif(not (CHECKOUT / "pyproject.toml").is_file(), reason="needs the checkout")
def test_wheel_installs_and_works_from_any_directory(tmp_path):
    # The wheel is built from a copy of what it is made of: built in the checkout, setuptools
    # would reuse its build/ folder and ship modules deleted since the last build.
    sources = tmp_path / "sources"
    for part in ("src", "data/harp"):
        shutil.copytree(
            CHECKOUT / part,
            sources / part,
            symlinks=True,
            ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"),
        )
    for part in ("pyproject.toml", "README.md"):
        shutil.copy(CHECKOUT / part, sources / part)
    wheels = tmp_path / "wheels"
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            "--no-deps",
            "--no-build-isolation",
            "--quiet",
            "--wheel-dir",
            str(wheels),
            str(sources),
        ],
        check=True,
        cwd=tmp_path,
        capture_output=True,
    )
    fresh = tmp_path / "fresh"
    venv.create(fresh, with_pip=False)
    python = fresh / "bin" / "python"
    purelib = Path(
        subprocess.run(
            [python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
            check=True,
            capture_output=True,
            text=True,
        ).stdout.strip()
    )
    # the dependencies come from this environment's site-packages, listed as a plain path so
    # its own .pth files (the editable install of the checkout) are not processed
    (purelib / "dependencies.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "install",
            "--no-deps",
            "--no-index",
            "--quiet",
            "--target",
            str(purelib),
            *map(str, wheels.glob("*.whl")),
        ],
        check=True,
        capture_output=True,
    )
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    result = subprocess.run(
        [python, "-c", SCRIPT],
        cwd=elsewhere,
        capture_output=True,
        text=True,
        env={"PATH": "/usr/bin:/bin", "MPLBACKEND": "Agg"},
    )
    assert result.returncode == 0, result.stderr[-3000:]
    package = Path(harp_analysis.__file__).parent
    every_module = [p for p in package.rglob("*.py") if not p.name.startswith("_")]
    subpackages = [p for p in package.rglob("__init__.py") if p.parent != package]
    assert int(result.stdout.split()[0]) == len(every_module) + len(subpackages)
