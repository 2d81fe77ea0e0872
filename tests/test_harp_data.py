"""Tests of the HARP appendix tables, their loader and the launch sites."""

from __future__ import annotations

import hashlib
import math
import shutil

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from harp_analysis.analyses.harp import appendices
from harp_analysis.analyses.harp.appendices import (
    MUZZLE_SPEEDS_FILE,
    PLAUSIBLE_RANGES,
    HarpDataError,
    load_appendix,
    load_barbados,
    load_muzzle_speeds,
    load_yuma,
    verify_checksums,
)
from harp_analysis.foundation.paths import HARP_DATA_DIR
from harp_analysis.models.sites import BARBADOS, YUMA, dms_to_deg, get_site

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


# --- plausible ranges ----------------------------------------------------------------------------
def test_every_column_has_documented_bounds():
    assert set(PLAUSIBLE_RANGES) == set(appendices._COLUMNS) | {"vo_ft_s"}
    for bounds in PLAUSIBLE_RANGES.values():
        assert bounds.low < bounds.high and bounds.reason


YUMA_ROW_6 = (
    "4\t0.94\t126.49\t83.916\t1.81\t5.36\t11.91\t0.16\t0.07\t73.17\t1.88\t86.62\t3473.46\t0.94"
)


def _with_field(site, column, value):
    """The test row of ``site`` (line, text) with ``column`` set to ``value``."""
    line, row = {"barbados": (7, BARBADOS_ROW_7), "yuma": (6, YUMA_ROW_6)}[site]
    fields = row.split("\t")
    fields[appendices._LAYOUTS[site][1].index(column)] = value
    return line, "\t".join(fields)


@pytest.mark.parametrize(
    "site, column, value, bounds",
    [
        ("barbados", "mass_kg", "-83.2356", r"\(50, 150\) kg"),
        ("barbados", "mass_kg", "183.5", r"\(50, 150\) kg"),  # pounds
        ("barbados", "apogee_km", "119000", r"\(10, 500\) km"),  # metres
        ("barbados", "vo_km_s", "1770", r"\(1, 5\) km/s"),
        ("barbados", "mach", "0.9", r"\(1, 20\)"),
        ("barbados", "mu_deg", "-14.01", r"\[1, 30\] deg"),
        ("barbados", "mu_deg", "0.24", r"\[1, 30\] deg"),  # radians
        ("yuma", "mu_deg", "0.21", r"\[1, 30\] deg"),  # radians
        ("barbados", "v_tangent_km_s", "-0.08", r"\[0, 6\) km/s"),
        ("barbados", "corrected_elevation_deg", "91", r"\[10, 90\) deg"),
        ("barbados", "corrected_elevation_deg", "1.24", r"\[10, 90\) deg"),  # radians
        ("barbados", "corrected_velocity_km_s", "1e999", r"\(0, 6\) km/s"),
        ("barbados", "corrected_azimuth_deg", "361", r"\[79, 139\] deg"),
        ("barbados", "corrected_azimuth_deg", "1.66", r"\[79, 139\] deg"),  # radians
        ("yuma", "corrected_azimuth_deg", "1.51", r"\[48, 108\] deg"),  # radians
        ("barbados", "beta", "0", r"\(0, 5\)"),
        ("barbados", "li_km2_s", "3.82102e9", r"\(0, 40000\) km2/s"),
        ("barbados", "round", "0", r"\[1, inf\)"),
        ("yuma", "error_km", "940", r"\(-100, 100\) km"),
        ("yuma", "delta_apogee_km", "-100", r"\(-100, 100\) km"),
    ],
)
def test_implausible_value_raises_naming_file_line_column(tmp_path, site, column, value, bounds):
    line, text = _with_field(site, column, value)
    path = _write(tmp_path, site, line, text)
    pattern = rf"line {line}, column '{column}': '{value}' is outside the plausible range {bounds}"
    with pytest.raises(HarpDataError, match=pattern) as info:
        load_appendix(site, path=path)
    assert str(path) in str(info.value)


@pytest.mark.parametrize(
    "column, value",
    [
        ("mu_deg", "1"),
        ("mu_deg", "30"),
        ("corrected_elevation_deg", "10"),
        ("corrected_azimuth_deg", "79"),
        ("corrected_azimuth_deg", "139"),
        ("v_tangent_km_s", "0"),
        ("round", "1"),
    ],
)
def test_closed_bounds_are_accepted(tmp_path, column, value):
    path = _write(tmp_path, "barbados", *_with_field("barbados", column, value))
    assert len(load_appendix("barbados", path=path)) == 23


@pytest.mark.parametrize(
    "text", [" 83.2356", "83.2356 ", "8_3.2356", "inf", "-nan", "0x53", "83,2356", "٨٣.٢"]
)
def test_numbers_must_be_plain_decimals(tmp_path, text):
    path = _write(tmp_path, "barbados", 7, BARBADOS_ROW_7.replace("83.2356", text))
    with pytest.raises(HarpDataError, match=r"line 7, column 'mass_kg': could not parse"):
        load_appendix("barbados", path=path)


def test_header_only_file_is_refused(tmp_path):
    for site, header_line in (("barbados", 5), ("yuma", 5)):
        lines = _write(tmp_path, site).read_text().splitlines()[:header_line]
        path = tmp_path / f"{site}_header_only.tsv"
        path.write_text("\n".join([*lines, "# a trailing comment"]) + "\n")
        with pytest.raises(HarpDataError, match="header but no data rows") as info:
            load_appendix(site, path=path)
        assert str(path) in str(info.value)
    path = tmp_path / "speeds.tsv"
    path.write_text("# comment\nsite\tround\tvo_ft_s\n")
    with pytest.raises(HarpDataError, match="header but no data rows") as info:
        load_muzzle_speeds("yuma", path)
    assert str(info.value).startswith(f"{path}: ")


@pytest.mark.parametrize(
    "row, pattern",
    [
        ("yuma\t4\t59300", r"line 3, column 'vo_ft_s': '59300' is outside .*\(3281, 16404\) ft/s"),
        ("yuma\t4\t1.81", r"column 'vo_ft_s': '1.81' is outside"),
        ("yuma\t4\t1807.5", r"column 'vo_ft_s': '1807.5' is outside .* in m/s"),  # m/s
        ("yuma\t0\t5930", r"column 'round': '0' is outside"),
        ("Yuma\t4\t5930", r"line 3, column 'site': 'Yuma' is not one of"),
        ("barbados\t4\t5930", r"no rows for site 'yuma'"),
    ],
)
def test_speed_file_bounds_name_the_line(tmp_path, row, pattern):
    path = tmp_path / "speeds.tsv"
    path.write_text(f"# comment\nsite\tround\tvo_ft_s\n{row}\n")
    with pytest.raises(HarpDataError, match=pattern) as info:
        load_muzzle_speeds("yuma", path)
    assert str(path) in str(info.value)


# --- checksums on load ---------------------------------------------------------------------------
@pytest.fixture
def package_copy(tmp_path, monkeypatch):
    """A copy of the package's data folder that the loaders take for their own (path=None)."""
    copy = tmp_path / "harp"
    copy.mkdir()
    for name in ("SHA256SUMS", *verify_checksums()):
        shutil.copy(HARP_DATA_DIR / name, copy / name)
    monkeypatch.setattr(appendices, "HARP_DATA_DIR", copy)
    return copy


def _edit(path, old, new):
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))


def test_edited_package_file_is_detected_and_verify_false_opts_out(package_copy):
    original = load_barbados()
    _edit(package_copy / "appendix_d_barbados.tsv", "181\t122\t", "181\t123\t")  # still plausible
    for load in (load_barbados, lambda **kw: load_appendix("barbados", **kw)):
        with pytest.raises(HarpDataError, match=r"appendix_d_barbados.tsv: SHA-256 .* was edited"):
            load()
        with pytest.raises(HarpDataError, match="verify=False"):
            load()
        edited = load(verify=False)
        assert edited["apogee_m"].iloc[0] == 123_000.0
        assert edited.drop(columns="apogee_m").equals(original.drop(columns="apogee_m"))
    assert len(load_yuma()) == 22  # the other files still verify


def test_edited_speed_file_is_detected(package_copy):
    _edit(package_copy / MUZZLE_SPEEDS_FILE, "yuma\t4\t5930", "yuma\t4\t5940")
    with pytest.raises(HarpDataError, match=rf"{MUZZLE_SPEEDS_FILE}: SHA-256 .* was edited"):
        load_muzzle_speeds("yuma")
    assert load_muzzle_speeds("yuma", verify=False)["speed_ft_s"].iloc[0] == 5940


def test_own_file_is_verified_only_where_a_sha256sums_lists_it(package_copy, tmp_path):
    path = package_copy / "appendix_e_yuma.tsv"
    assert load_appendix("yuma", path=path).equals(load_yuma())
    _edit(path, "4\t0.94\t", "4\t0.95\t")
    with pytest.raises(HarpDataError, match="was edited"):
        load_appendix("yuma", path=path)
    assert load_appendix("yuma", path=path, verify=False)["apogee_error_m"].iloc[0] == 950.0
    (package_copy / "SHA256SUMS").unlink()  # a folder without a listing: nothing to check against
    assert load_appendix("yuma", path=path)["apogee_error_m"].iloc[0] == 950.0


def test_package_file_must_be_listed(package_copy):
    sums = package_copy / "SHA256SUMS"
    sums.write_text("".join(line + "\n" for line in sums.read_text().splitlines()[1:]))
    with pytest.raises(HarpDataError, match=r"appendix_d_barbados.tsv: not listed in"):
        load_barbados()
    assert len(load_barbados(verify=False)) == 23
    sums.unlink()
    with pytest.raises(HarpDataError, match="no SHA256SUMS"):
        load_yuma()


@pytest.mark.parametrize(
    "line, pattern",
    [
        ("abc", r"SHA256SUMS line 2: malformed line 'abc'"),
        ("0" * 64, r"SHA256SUMS line 2: malformed line"),
        ("0" * 63 + "  a.tsv", r"SHA256SUMS line 2: '0{63}' is not a SHA-256 digest \(64 hex"),
        ("g" * 64 + "  a.tsv", r"SHA256SUMS line 2: 'g{64}' is not a SHA-256 digest"),
        ("0" * 64 + "  *", r"SHA256SUMS line 2: malformed line .*no file name"),
        ("0" * 64 + "  a.tsv", r"SHA256SUMS line 2: a.tsv is listed twice"),
    ],
)
def test_malformed_sha256sums_line_is_named(tmp_path, line, pattern):
    (tmp_path / "a.tsv").write_text("x\n")
    digest = hashlib.sha256(b"x\n").hexdigest()
    (tmp_path / "SHA256SUMS").write_text(f"{digest}  a.tsv\n{line}\n")
    with pytest.raises(HarpDataError, match=pattern):
        verify_checksums(tmp_path)


def test_sha256sums_blank_lines_star_names_and_upper_case_hex_are_accepted(tmp_path):
    (tmp_path / "a.tsv").write_text("x\n")
    digest = hashlib.sha256(b"x\n").hexdigest().upper()
    (tmp_path / "SHA256SUMS").write_text(f"\n{digest} *a.tsv\n\n")
    assert verify_checksums(tmp_path) == ["a.tsv"]


def test_malformed_sha256sums_fails_a_verified_load(package_copy):
    with (package_copy / "SHA256SUMS").open("a") as sums:
        sums.write("not-a-checksum-line\n")
    with pytest.raises(HarpDataError, match=r"SHA256SUMS line 4: malformed line"):
        load_yuma()
    assert len(load_yuma(verify=False)) == 22


# --- fuzz: a loader returns plausible values or raises HarpDataError ---------------------------
def _file_lines(name):
    """(comment lines, header, data rows as lists of fields) of a packaged file."""
    lines = (HARP_DATA_DIR / name).read_text().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    header, *rows = [line for line in lines if not line.startswith("#")]
    return comments, header, [row.split("\t") for row in rows]


FIELDS = st.one_of(
    st.text(max_size=12),
    st.text(alphabet="0123456789.-+eE\t #", max_size=10),
    st.floats().map(repr),
    st.floats(-1e6, 1e6).map(lambda x: f"{x:.4g}"),
    st.floats(-1, 400).map(lambda x: f"{x:.3f}"),  # near and inside most bounds
    st.integers(-(10**6), 10**6).map(str),
    st.sampled_from(["", "nan", "inf", "-0", "1e999", "0x10", "1_000"]),
)


@st.composite
def _file_text(draw, name):
    comments, header, rows = _file_lines(name)
    width = len(rows[0])

    def mutated(row, index, field):
        return "\t".join(row[:index] + [field] + row[index + 1 :])

    valid = st.sampled_from(rows).map("\t".join)
    one_bad_field = st.builds(mutated, st.sampled_from(rows), st.integers(0, width - 1), FIELDS)
    random_fields = st.lists(FIELDS, min_size=max(width - 2, 0), max_size=width + 2)
    odd_line = st.sampled_from(["# comment", "", "\t" * (width - 1)])
    # Valid rows with up to two others slipped in, so that some files load and get checked.
    body = draw(st.lists(valid, max_size=4))
    for _ in range(draw(st.integers(0, 2))):
        other = draw(st.one_of(one_bad_field, random_fields.map("\t".join), odd_line))
        body.insert(draw(st.integers(0, len(body))), other)
    return "\n".join([*comments, header, *body]) + draw(st.sampled_from(["", "\n", "\r\n"]))


def _assert_plausible(frame, columns):
    assert len(frame) > 0
    for column in columns:
        bounds = PLAUSIBLE_RANGES[column]
        loaded, scale = appendices._COLUMNS[column]
        scale = 1 if scale is None else scale
        values = frame[loaded].to_numpy(dtype=float)
        # Scaling is monotonic, so a value inside the printed bounds stays inside the scaled ones.
        assert np.isfinite(values).all()
        assert (values >= bounds.low * scale).all() and (values <= bounds.high * scale).all()


@pytest.mark.parametrize("site", ["barbados", "yuma"])
@settings(max_examples=100, deadline=None)
@given(data=st.data())
def test_fuzzed_appendix_loads_plausible_values_or_raises_harp_data_error(
    tmp_path_factory, site, data
):
    name = appendices._LAYOUTS[site][0]
    text = data.draw(_file_text(name))
    path = tmp_path_factory.mktemp("fuzz") / name
    path.write_text(text, encoding="utf-8", newline="")
    try:
        frame = load_appendix(site, path=path)
    except HarpDataError as error:
        assert str(path) in str(error)
        return
    _assert_plausible(frame, appendices._LAYOUTS[site][1])
    assert frame["round_number"].dtype.kind == "i"


@settings(max_examples=100, deadline=None)
@given(data=st.data())
def test_fuzzed_speed_file_loads_plausible_values_or_raises_harp_data_error(tmp_path_factory, data):
    text = data.draw(_file_text(MUZZLE_SPEEDS_FILE))
    path = tmp_path_factory.mktemp("fuzz") / MUZZLE_SPEEDS_FILE
    path.write_text(text, encoding="utf-8", newline="")
    try:
        frame = load_muzzle_speeds("yuma", path=path)
    except HarpDataError as error:
        assert str(path) in str(error)
        return
    assert len(frame) > 0 and not frame["round_number"].duplicated().any()
    assert frame["round_number"].min() >= 1
    assert frame["speed_ft_s"].between(1000, 15000, inclusive="neither").all()
    np.testing.assert_array_equal(frame["muzzle_speed_m_s"], frame["speed_ft_s"] * FOOT_M)
