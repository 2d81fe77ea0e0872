"""The curated public API: the names a user starts from, importable from the package itself,
each imported on first use so that ``import harp_analysis`` starts no compiler."""

import importlib
import subprocess
import sys

import pytest

import harp_analysis


def test_importing_the_package_loads_no_engine_and_no_numba():
    script = (
        "import sys, harp_analysis; print(sorted(m for m in sys.modules"
        " if 'numba' in m or m.startswith('harp_analysis.')))"
    )
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True)
    assert run.stdout.strip() == "[]"


@pytest.mark.parametrize("name", [n for n in harp_analysis.__all__ if n != "__version__"])
def test_each_public_name_is_its_module_s_object(name):
    module = importlib.import_module(f"harp_analysis.{harp_analysis._API[name]}")
    assert getattr(harp_analysis, name) is getattr(module, name)
    assert name in dir(harp_analysis)


def test_an_unknown_name_is_an_attribute_error_naming_it():
    with pytest.raises(AttributeError, match="has no attribute 'simulate_4dof'"):
        harp_analysis.simulate_4dof  # noqa: B018
    from harp_analysis.engines import mks  # submodules import as ever

    assert mks.__name__ == "harp_analysis.engines.mks"


def test_a_launch_flies_from_the_top_level_names():
    from harp_analysis import HP_CHAPTER_2, simulate_mks

    assert simulate_mks(HP_CHAPTER_2, warn=False).attrs["engine"] == "MKS"
