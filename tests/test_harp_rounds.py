"""Tests of single HARP rounds: the Earth-fixed ECI MKS trajectory, radar tracks, the figure."""

from __future__ import annotations

import math

import numpy as np
import pytest
from matplotlib.figure import Figure

from harp_analysis.analyses.harp import apogees as harp
from harp_analysis.analyses.harp import rounds as harp_rounds
from harp_analysis.analyses.harp.appendices import HarpDataError
from harp_analysis.engines import eci
from harp_analysis.foundation import earth
from harp_analysis.models.sites import BARBADOS
from harp_analysis.reporting.figures import harp as harp_figures

GOOD_TRACK = """# source: test fixture, not data
time_s,altitude_km,range_km,radar
10.0,17.5,0.6,MPS-19
20.0,33.0,1.2,M-33
"""


@pytest.fixture(scope="module")
def round_181():
    return harp_rounds.round_trajectory("barbados", 181)


@pytest.fixture
def radar_dir(tmp_path, monkeypatch):
    monkeypatch.setattr(harp_rounds, "RADAR_DIR", tmp_path)
    return tmp_path


def test_starts_at_gun_and_peaks_at_eq_6_4_apogee(round_181):
    first = round_181.iloc[0]
    assert first.time_s == 0 and abs(first.altitude_m) < 1e-3
    assert np.allclose(
        first[["ground_range_m", "downrange_m", "cross_range_m", "radar_range_m"]].to_numpy(float),
        0,
        atol=1e-3,
    )
    apogees = harp.predicted_apogees("barbados").drop_duplicates("round_number")
    apogee_m = dict(zip(apogees.round_number, apogees.predicted_apogee_m))
    for number, frame in ((181, round_181), (206, harp_rounds.round_trajectory("barbados", 206))):
        assert frame.altitude_m.max() == pytest.approx(apogee_m[number], abs=2.0)
    assert abs(round_181.altitude_m.iloc[-1]) < 1e-3 and round_181.time_s.is_monotonic_increasing


def test_earth_fixed_range_lags_inertial_by_site_motion(round_181):
    """R theta - ground range ~ omega R cos(lat) t along the inertial azimuth (within 5%)."""
    _, _, row = harp_rounds.round_row("barbados", 181)
    azimuth = eci.correction_for_arrays(
        row.muzzle_speed_m_s,
        BARBADOS.elevation_rad,
        BARBADOS.gun_bearing_rad,
        BARBADOS.latitude_rad,
        drag_area_m2=harp.drag_area_m2(),
        mass_kg=row.mass_kg,
        surface_density_kg_m3=1.225,
        model="dissertation",
    ).azimuth_rad
    later = round_181.iloc[1:]
    site_motion = (
        earth.ROTATION_RATE_RAD_S
        * earth.RADIUS_M
        * math.cos(BARBADOS.latitude_rad)
        * later.time_s
        * math.sin(azimuth)
    )
    ratio = (later.inertial_range_m - later.ground_range_m) / site_motion
    assert ratio.between(0.95, 1.05).all()
    assert np.allclose(
        np.hypot(later.downrange_m, later.cross_range_m), later.ground_range_m, rtol=1e-3
    )
    assert (round_181.radar_range_m == round_181.ground_range_m).all()


def test_splash_range_is_the_great_circle_to_the_moved_site():
    """Independently of the module: the MKS impact point in the inertial frame and the gun site
    carried round by the Earth during the flight are a great-circle distance apart."""
    _, _, row = harp_rounds.round_row("barbados", 181)
    options = dict(
        drag_area_m2=harp.drag_area_m2(),
        mass_kg=row.mass_kg,
        surface_density_kg_m3=BARBADOS.surface_density_kg_m3,
        model="dissertation",
    )
    arguments = (
        row.muzzle_speed_m_s,
        BARBADOS.elevation_rad,
        BARBADOS.gun_bearing_rad,
        BARBADOS.latitude_rad,
    )
    launch = eci.correction_for_arrays(*arguments, **options)
    solution = launch.solution(warn=False)
    up = np.array([math.cos(BARBADOS.latitude_rad), 0.0, math.sin(BARBADOS.latitude_rad)])
    velocity = np.ravel(launch.velocity_m_s)
    along = velocity - (velocity @ up) * up
    along /= np.linalg.norm(along)
    theta = float(solution.impact_angle)
    flight_s = float(solution.time(np.linspace(0.0, theta, 400))[-1])
    impact = math.cos(theta) * up + math.sin(theta) * along
    turn = earth.ROTATION_RATE_RAD_S * flight_s
    site = np.array([math.cos(turn) * up[0], math.sin(turn) * up[0], up[2]])
    distance_km = earth.RADIUS_M * math.acos(impact @ site) / 1e3
    assert harp_rounds.splash_range_km() == pytest.approx(distance_km, abs=0.05)
    # The text's MKS range, 39.6 km, within the ledger's close tolerance (ch6.round181.range).
    assert distance_km == pytest.approx(39.6, abs=0.5)


def test_missing_round_and_unknown_site_are_named():
    with pytest.raises(ValueError, match="round 227 .*Barbados"):
        harp_rounds.round_trajectory("barbados", 227)
    with pytest.raises(ValueError, match="site 'mars'"):
        harp_rounds.round_trajectory("mars", 181)
    with pytest.raises(ValueError, match="n_points"):
        harp_rounds.round_trajectory("barbados", 181, n_points=1)


def test_no_radar_file_gives_none_and_the_caption_says_so(radar_dir):
    """Without a radar file the figure draws no radar series and, a note being caption text,
    writes none on the page (its one text is the title naming the case): the registry's
    caption says the tracks are not in the text."""
    from harp_analysis.reporting.registry import get_entry

    assert harp_rounds.load_radar_track("barbados", 181) is None
    fig = harp_figures.draw_round_figure("barbados", 181)
    assert [t.get_text() for t in fig.texts] == [fig.get_suptitle()]
    labels = {line.get_label() for ax in fig.axes for line in ax.get_lines()}
    assert not any("radar" in label for label in labels)
    for number in ("6.7", "6.8", "6.10"):
        assert "the radar tracks are not in the dissertation" in get_entry(number).caption


def test_radar_track_loads_in_si_and_is_drawn(radar_dir):
    (radar_dir / "barbados_round_188.csv").write_text(GOOD_TRACK)
    track = harp_rounds.load_radar_track("Barbados", 188)
    assert track.altitude_m.tolist() == [17500.0, 33000.0]
    assert track.range_m.tolist() == [600.0, 1200.0]
    assert track.radar.tolist() == ["MPS-19", "M-33"] and track.source_line.tolist() == [3, 4]
    assert "test fixture" in track.attrs["provenance"]
    fig = harp_figures.draw_round_figure("barbados", 188)
    assert isinstance(fig, Figure)
    assert not any("not in the dissertation" in t.get_text() for t in fig.texts)
    labels = {line.get_label() for line in fig.axes[1].get_lines()}
    assert {"MPS-19 radar", "M-33 radar", "ECI Modified Kepler"} <= labels


@pytest.mark.parametrize(
    "text, where",
    [
        (GOOD_TRACK.replace("33.0", "3x"), "line 4, column 'altitude_km'"),
        (GOOD_TRACK.replace(",M-33", ",FPS-16"), "line 4, column 'radar'"),
        (GOOD_TRACK.replace("10.0,17.5,0.6,", "10.0,17.5,"), "line 3, column 'radar'"),
        (GOOD_TRACK.replace("0.6", "-0.6"), "line 3, column 'range_km'"),
        (GOOD_TRACK.replace("range_km", "range_m"), "line 2: header"),
        (GOOD_TRACK.replace("# source:", "# from:"), "source"),
    ],
)
def test_malformed_radar_file_is_named(radar_dir, text, where):
    (radar_dir / "barbados_round_206.csv").write_text(text)
    with pytest.raises(HarpDataError, match="barbados_round_206.csv") as error:
        harp_rounds.load_radar_track("barbados", 206)
    assert where in str(error.value)
