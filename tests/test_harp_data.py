"""Tests of the HARP appendix tables, their loader and the launch sites."""

from __future__ import annotations

import math

import numpy as np
import pytest

from harp_analysis.harp_data import (
    HarpDataError,
    load_appendix,
    load_barbados,
    load_yuma,
    verify_checksums,
)
from harp_analysis.paths import HARP_DATA_DIR
from harp_analysis.sites import BARBADOS, YUMA, dms_to_deg, get_site

FOOT_M = 0.3048
POUND_KG = 0.4536  # the factor used in the dissertation's tables, not the exact 0.45359237


@pytest.fixture(scope="module")
def barbados():
    return load_barbados()


@pytest.fixture(scope="module")
def yuma():
    return load_yuma()


def test_checksums_verify():
    assert verify_checksums() == [
        "appendix_d_barbados.tsv",
        "appendix_e_yuma.tsv",
        "muzzle_speeds.tsv",
    ]


def test_checksum_mismatch_names_file(tmp_path):
    (tmp_path / "a.tsv").write_text("x\n")
    (tmp_path / "SHA256SUMS").write_text("0" * 64 + "  a.tsv\n")
    with pytest.raises(HarpDataError, match="a.tsv"):
        verify_checksums(tmp_path)


def test_row_counts_and_order(barbados, yuma):
    assert len(barbados) == 23 and len(yuma) == 22
    assert barbados["round_number"].iloc[[0, -2, -1]].tolist() == [181, 205, 181]
    assert yuma["round_number"].tolist()[:3] == [4, 5, 8]
    assert barbados["source_line"].iloc[0] == 6 and barbados["source_line"].is_monotonic_increasing


def test_only_last_barbados_row_is_duplicate(barbados, yuma):
    assert barbados["duplicate_of_earlier_row"].tolist() == [False] * 22 + [True]
    assert not yuma["duplicate_of_earlier_row"].any()
    first, last = barbados.iloc[0], barbados.iloc[-1]
    assert first.drop(["duplicate_of_earlier_row", "source_line"]).equals(
        last.drop(["duplicate_of_earlier_row", "source_line"])
    )


def test_si_conversions(barbados, yuma):
    r206 = barbados.set_index("round_number").loc[206]
    assert r206["apogee_m"] == pytest.approx(137_000.0)
    assert r206["initial_angular_momentum_m2_s"] == pytest.approx(3.90621e9)
    assert r206["muzzle_speed_m_s"] == pytest.approx(1930.0)
    assert r206["mass_kg"] == pytest.approx(83.916)
    assert r206["corrected_elevation_rad"] == pytest.approx(math.radians(72.30))
    r4 = yuma.set_index("round_number").loc[4]
    assert r4["apogee_error_m"] == pytest.approx(940.0)
    assert r4["misalignment_angle_rad"] == pytest.approx(math.radians(11.91))
    assert r4["tangent_speed_m_s"] == pytest.approx(70.0)
    assert set(barbados["site"]) == {"Barbados"} and set(yuma["site"]) == {"Yuma"}
    assert barbados["round_number"].dtype.kind == "i"


def test_yuma_error_equals_delta_apogee(yuma):
    assert (yuma["apogee_error_m"] == yuma["delta_apogee_m"]).all()


def test_yuma_apogees_are_whole_thousands_of_feet(yuma):
    thousands_ft = yuma["apogee_m"] / (1000 * FOOT_M)
    residual_m = (thousands_ft - thousands_ft.round()).abs() * 1000 * FOOT_M
    assert (residual_m <= 5.0 + 1e-9).all()  # printed to 0.01 km


@pytest.mark.parametrize("loader", [load_barbados, load_yuma])
def test_masses_are_half_pounds(loader):
    half_pounds = loader()["mass_kg"] / POUND_KG * 2
    np.testing.assert_allclose(half_pounds, half_pounds.round(), atol=1e-9)


def test_barbados_round_213_is_lighter(barbados):
    light = barbados[barbados["mass_kg"] < 80]
    assert light["round_number"].tolist() == [213]
    assert light["beta"].item() == 0.20 and set(barbados.drop(light.index)["beta"]) == {0.18}


def _write(tmp_path, site, replace_line=None, text=None):
    """Copy a site's file into tmp_path, optionally replacing one 1-based line."""
    name = {"barbados": "appendix_d_barbados.tsv", "yuma": "appendix_e_yuma.tsv"}[site]
    lines = (HARP_DATA_DIR / name).read_text().splitlines()
    if replace_line is not None:
        lines[replace_line - 1] = text
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n")
    return path


BARBADOS_ROW_7 = "188\t119\t83.2356\t1.77\t5.15\t14.01\t0.08\t71.21\t1.86\t95.03\t0.18\t3821.02"


@pytest.mark.parametrize(
    "line, text, pattern",
    [
        (
            7,
            BARBADOS_ROW_7.replace("83.2356", "x83.2"),
            r"line 7, column 'mass_kg': could not parse 'x83.2'",
        ),
        (7, BARBADOS_ROW_7.rsplit("\t", 1)[0], r"line 7, column 'li_km2_s': missing field"),
        (7, BARBADOS_ROW_7 + "\t1", r"line 7, column 'li_km2_s': extra fields"),
        (
            7,
            BARBADOS_ROW_7.replace("188", "188.0", 1),
            r"line 7, column 'round': could not parse '188.0'",
        ),
        (
            7,
            BARBADOS_ROW_7.replace("119", "nan"),
            r"line 7, column 'apogee_km': could not parse 'nan'",
        ),
        (7, BARBADOS_ROW_7.replace("0.18", ""), r"line 7, column 'beta': could not parse ''"),
        (5, "round\tapogee\tmass_kg", r"line 5: header"),
    ],
)
def test_malformed_file_raises_naming_file_line_column(tmp_path, line, text, pattern):
    path = _write(tmp_path, "barbados", line, text)
    with pytest.raises(HarpDataError, match=pattern) as info:
        load_appendix("barbados", path=path)
    assert str(path) in str(info.value)


def test_yuma_layout_rejects_barbados_file(tmp_path):
    with pytest.raises(HarpDataError, match="line 5: header"):
        load_appendix("yuma", path=_write(tmp_path, "barbados"))


def test_copy_loads_like_original(tmp_path):
    assert load_appendix("Yuma", path=_write(tmp_path, "yuma")).equals(load_yuma())


@pytest.mark.parametrize("bad", ["mars", "", "barbados ", None])
def test_unknown_site_raises_naming_site(bad):
    with pytest.raises(ValueError, match=r"site .*'barbados', 'yuma'"):
        get_site(bad)
    with pytest.raises(ValueError, match="site"):
        load_appendix(bad)


@pytest.mark.parametrize(
    "name, site", [("barbados", BARBADOS), ("BARBADOS", BARBADOS), ("Yuma", YUMA)]
)
def test_get_site_is_case_insensitive(name, site):
    assert get_site(name) is site


def test_barbados_latitude_gives_eq_6_16_surface_speed():
    assert math.degrees(BARBADOS.latitude_rad) == pytest.approx(13.0772, abs=5e-5)
    surface_speed_km_s = 2 * math.pi / 86400 * 6378 * math.cos(BARBADOS.latitude_rad)
    assert round(surface_speed_km_s, 4) == 0.4518


def test_site_values():
    assert math.degrees(YUMA.latitude_rad) == pytest.approx(32 + 52 / 60 + 33 / 3600)
    assert math.degrees(BARBADOS.gun_bearing_rad) == pytest.approx(109.0)
    assert math.degrees(YUMA.gun_bearing_rad) == pytest.approx(78.0)
    assert (BARBADOS.surface_density_kg_m3, YUMA.surface_density_kg_m3) == (1.225, 1.14)
    assert BARBADOS.elevation_rad == YUMA.elevation_rad == pytest.approx(math.radians(85.0))


def test_dms_to_deg():
    assert dms_to_deg(13, 4, 38) == pytest.approx(13.0772222222)
    assert dms_to_deg(-13, 30, 0) == -13.5
    for minutes, seconds, name in [(60, 0, "minutes"), (0, -1, "seconds")]:
        with pytest.raises(ValueError, match=name):
            dms_to_deg(13, minutes, seconds)
