"""The explorer without a browser: set the controls as a reader would, check what the views
show against the engines flown directly, and that bad input shows as a message.
"""

import html
import math
import re
import runpy
import warnings
from dataclasses import replace
from functools import cache
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from tornado.web import HTTPError
from traitlets.config import Config

from harp_analysis.analyses import mks_improvement
from harp_analysis.analyses.harp import apogees
from harp_analysis.engines import calibrated_mks, mks, mks_improved, threedof
from harp_analysis.foundation import earth
from harp_analysis.models.launch import HP_CHAPTER_2, Launch
from harp_analysis.models.projectiles import BASELINE, HP
from harp_analysis.reporting import explorer


def _numbers(summary: str) -> dict[str, list[float]]:
    """The summary table's rows: engine -> apogee (km), its time, range (km), time of flight."""
    rows = re.findall(r"<tr><td>([^<]+)</td>(.*?)</tr>", summary)
    return {
        engine: [float(v) for v in re.findall(r"<td>([-0-9.]+)</td>", cells)]
        for engine, cells in rows
    }


def _direct(launch):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        three = threedof.simulate_3dof(launch).attrs
        solution = mks_improved.dissertation(launch)
    return three, solution


@pytest.fixture(scope="module")
def hp():
    return explorer.Explorer("Chapter 2 A: HP")


def test_opens_on_chapter_2s_hp_with_both_engines_numbers(hp):
    three, solution = _direct(HP_CHAPTER_2)
    numbers = _numbers(hp.summary.value)
    assert numbers["3DOF"][0] == pytest.approx(three["apogee_altitude_m"] / 1e3, abs=5e-4)
    assert numbers["3DOF"][2] == pytest.approx(three["range_m"] / 1e3, abs=5e-4)
    assert numbers["MKS"][0] == pytest.approx(solution.apogee_altitude_m / 1e3, abs=5e-4)
    assert numbers["MKS"][3] == pytest.approx(solution.impact_time_s, abs=0.05)
    assert bytes(hp.plot.value[:4]) == b"\x89PNG"
    messages = html.unescape(hp.messages.value)
    assert '"Cross wind (m/s)" = 5' in messages  # the MKS leaves Chapter 2's wind out
    assert "beta = 0.275" in messages  # above the text's 0.25


def test_a_moved_slider_flies_the_new_launch(hp):
    before_plot, before = hp.plot.value, _numbers(hp.summary.value)
    hp.controls["elevation_deg"].value = 62.0
    after = _numbers(hp.summary.value)
    assert bytes(hp.plot.value) != bytes(before_plot)
    assert after["3DOF"][0] > before["3DOF"][0]  # steeper, higher
    moved = Launch(HP, HP.launch_speed_m_s, 62.0, cross_wind_m_s=5.0, spin_rad_s=10.0)
    three, _ = _direct(moved)
    assert after["3DOF"][0] == pytest.approx(three["apogee_altitude_m"] / 1e3, abs=5e-4)
    assert hp.preset.value == "(your own)"  # no longer the dissertation's case
    hp.preset.value = "Chapter 2 A: HP"
    assert hp.controls["elevation_deg"].value == 50.0
    assert _numbers(hp.summary.value) == before


def test_a_harp_round_flies_the_martlet_and_shows_the_measured_apogee():
    presets = explorer.presets()
    name = next(n for n in presets if n.startswith("HARP Yuma"))
    view = explorer.Explorer(name)
    setting = presets[name]
    launch = explorer.launch_for(setting)
    assert launch.projectile.reference_area_m2 == pytest.approx(apogees.drag_area_m2())
    assert launch.elevation_deg == 85.0 and launch.rotation_rate_rad_s > 0
    # Yuma's 1.14 kg/m^3 as the day's change of the MKS's sea-level 1.225 kg/m^3
    assert mks.gun_density_kg_m3(launch) == pytest.approx(1.14, rel=1e-12)
    numbers = _numbers(view.summary.value)
    assert numbers["measured (HARP)"][0] == pytest.approx(
        setting.measured_apogee_m / 1e3, abs=0.005
    )
    assert abs(numbers["MKS"][0] - numbers["3DOF"][0]) < 5.0  # km: the MKS's home ground


def test_a_custom_projectile_with_the_martlets_drag_flies_as_the_martlet():
    """Only Cd0 A and the mass enter a point-mass flight with constant Cd: any diameter."""
    martlet = explorer.launch_for(explorer.Settings(projectile="Martlet", mass_kg=83.0))
    custom = explorer.launch_for(
        explorer.Settings(
            projectile="custom", mass_kg=83.0, diameter_m=0.37, drag_area_m2=apogees.drag_area_m2()
        )
    )
    a, b = threedof.fly_3dof(martlet), threedof.fly_3dof(custom)
    assert a.apogee_altitude_m[0] == pytest.approx(b.apogee_altitude_m[0], rel=1e-8)


def test_6dof_and_mlt_come_on_request_and_refuse_what_they_cannot_fly():
    view = explorer.Explorer("Chapter 2 A: LP")
    assert set(_numbers(view.summary.value)) == {"3DOF", "MKS"}
    view.rigid_body.click()
    numbers = _numbers(view.summary.value)
    assert {"6DOF", "MLT"} <= set(numbers)
    assert numbers["6DOF"][0] == pytest.approx(numbers["3DOF"][0], rel=0.01)
    view.preset.value = "Chapter 4 B: baseline, 45 deg"  # a cone: no rigid-body data
    view.rigid_body.click()
    assert "cannot fly this launch" in view.messages.value
    assert {"3DOF", "MKS"} <= set(_numbers(view.summary.value))


@pytest.mark.parametrize(
    "changes, says",
    [
        ({"projectile": "custom", "mass_kg": 0.0}, "Mass (kg) must lie in (0, inf] kg; got 0"),
        ({"projectile": "custom", "diameter_m": -0.1}, "Diameter (m) must lie in (0, inf]"),
        ({"projectile": "custom", "drag_area_m2": -1e-3}, "Cd0 A (m^2) must lie in [0, inf]"),
        ({"speed_m_s": 300.0, "elevation_deg": 10.0}, "never leaves the sensible atmosphere"),
    ],
)
def test_bad_input_is_a_message_never_a_traceback(changes, says):
    view = explorer.Explorer("Chapter 4 B: baseline, 45 deg")
    for name, value in changes.items():
        view.controls[name].value = value
    assert says in view.messages.value


@pytest.mark.parametrize(
    "launch, shown",
    [
        (HP_CHAPTER_2, True),  # beta 0.275: shown, and warned of
        (Launch(BASELINE, 2157.0, 3.0), False),  # beta 1.44: the series fails, not shown
    ],
)
def test_the_mks_beta_is_one_message(launch, shown):
    """The MKS's own warning says its beta is beyond the text's 0.25, once, in its words;
    where the explorer hides the MKS (beta above 1), the same message says so."""
    flown, messages = explorer.fly(launch)
    about_beta = [text for text in messages if "beta" in text]
    assert len(about_beta) == 1, messages
    assert re.match(
        r"MKS beta = [\d.]+ > 0.25: the text finds the solution inaccurate", about_beta[0]
    )
    assert ("MKS" in flown) == shown
    assert ("no MKS is shown" in about_beta[0]) == (not shown)


def test_the_sensible_atmosphere_is_not_the_atmosphere_control():
    """A message's plain word "atmosphere" stays a word; only the field is the control's label."""
    _, messages = explorer.fly(Launch(BASELINE, 2157.0, 10.0))
    assert any("does not leave the sensible atmosphere" in text for text in messages), messages
    assert not any('"Atmosphere"' in text for text in messages), messages
    assert explorer.in_readers_words("launch.atmosphere = 1") == '"Atmosphere" = 1'


def test_a_round_that_escapes_is_said_to():
    """12 km/s is past the escape speed (11.2 km/s at the surface, before drag): no apogee."""
    launch = explorer.launch_for(explorer.Settings(projectile="baseline", speed_m_s=12e3))
    flown, messages = explorer.fly(launch)
    assert not math.isfinite(flown["3DOF"].apogee_m)
    assert any("reaches no apogee" in text for text in messages)


def test_a_launch_that_cannot_be_flown_leaves_nothing_of_the_last_one():
    view = explorer.Explorer("Chapter 4 B: baseline, 45 deg")
    view.controls["projectile"].value = "custom"
    view.controls["mass_kg"].value = 0.0
    assert view.summary.value == ""
    assert bytes(view.plot.value) == explorer.draw({})


def test_every_control_reaches_the_launch():
    """Each control set away from its default, the explorer's launch is the one built
    directly, field by field (a control that did not reach it would show here)."""
    view = explorer.Explorer("Chapter 4 B: baseline, 45 deg")
    values = {
        "projectile": "custom",
        "mass_kg": 40.0,
        "diameter_m": 0.12,
        "drag_area_m2": 3e-3,
        "speed_m_s": 1800.0,
        "elevation_deg": 55.0,
        "bearing_deg": 200.0,
        "latitude_deg": -35.0,
        "rotating": True,
        "cross_wind_m_s": 4.0,
        "head_wind_m_s": -3.0,
        "atmosphere": "us1976",
        "density_change_percent": 5.0,
        "temperature_change_k": -7.0,
        "spin_rad_s": 12.0,
    }
    for name, value in values.items():
        view.controls[name].value = value
    launch = explorer.launch_for(view.settings)
    assert launch.projectile.mass_kg == 40.0
    area = math.pi * 0.12**2 / 4
    assert launch.projectile.reference_area_m2 == pytest.approx(area)
    assert launch.launch_drag_coefficient * area == pytest.approx(3e-3)
    direct = Launch(
        launch.projectile,
        1800.0,
        55.0,
        bearing_deg=200.0,
        latitude_deg=-35.0,
        cross_wind_m_s=4.0,
        head_wind_m_s=-3.0,
        spin_rad_s=12.0,
        atmosphere="us1976",
        rotation_rate_rad_s=earth.ROTATION_RATE_RAD_S,
        density_change_fraction=0.05,
        temperature_change_k=-7.0,
    )
    assert launch == direct
    three, _ = _direct(direct)
    shown = _numbers(view.summary.value)["3DOF"]
    assert shown[0] == pytest.approx(three["apogee_altitude_m"] / 1e3, abs=5e-4)


def test_the_improved_mks_is_another_view_of_the_same_launch():
    """Ticking it adds the improved MKS's row and keeps the case, its measured apogee and the
    6DOF/MLT rows; a change of the launch drops the measured apogee."""
    presets = explorer.presets()
    name = next(n for n in presets if n.startswith("HARP Barbados"))
    view = explorer.Explorer(name)
    view.controls["improved_mks"].value = True
    numbers = _numbers(view.summary.value)
    assert {"3DOF", "MKS", "improved MKS", "measured (HARP)"} <= set(numbers)
    assert view.preset.value == name
    improved = mks_improved.solve(explorer.launch_for(view.settings), mks_improvement.calibration())
    assert numbers["improved MKS"][0] == pytest.approx(improved.apogee_altitude_m / 1e3, abs=5e-4)
    view.controls["elevation_deg"].value = 80.0
    assert "measured (HARP)" not in _numbers(view.summary.value)


def test_the_calibrated_mks_is_another_view_with_the_engines_own_numbers():
    """Ticked, the calibrated MKS is drawn and summed up as simulate_calibrated_mks flies it
    directly, its distance from the 3DOF measured at the 3DOF's times; its gun's table is
    learned on first use and said to be while it is (a still Earth's: a second or two)."""
    view = explorer.Explorer("Chapter 2 A: HP")
    said = []
    view.messages.observe(lambda change: said.append(change["new"]), names="value")
    view.controls["calibrated_mks"].value = True
    assert "Finding the calibrated MKS's table for this gun" in html.unescape(said[0])
    assert view.preset.value == "Chapter 2 A: HP"
    launch = explorer.launch_for(view.settings)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        table = calibrated_mks.simulate_calibrated_mks(launch)
    shown = _numbers(view.summary.value)["calibrated MKS"]
    attrs = table.attrs
    expected = [attrs["apogee_altitude_m"] / 1e3, attrs["apogee_time_s"], attrs["range_m"] / 1e3]
    assert shown[0] == pytest.approx(expected[0], abs=5e-4)  # km, to the metre
    assert shown[1] == pytest.approx(expected[1], abs=0.05)  # s, to the tenth
    assert shown[2] == pytest.approx(expected[2], abs=5e-4)
    assert shown[3] == pytest.approx(attrs["time_of_flight_s"], abs=0.05)
    flown = view.last_flown["calibrated MKS"]
    assert flown.path.equals(table[["time_s", "ground_range_m", "altitude_m"]])
    distance = flown.error_to_3dof
    assert 0 < len(distance) and distance.time_s.max() <= attrs["time_of_flight_s"]
    assert distance.distance_m.max() < 1e3  # its measured accuracy: ~0.1 km, wind left out
    assert 'the calibrated MKS ignores "Cross wind (m/s)" = 5' in html.unescape(view.messages.value)
    said.clear()
    view.controls["elevation_deg"].value = 60.0  # the same gun: nothing to learn
    assert not any("Finding" in text for text in said)
    view.controls["elevation_deg"].value = 10.0  # below its band: a message, the rest flown
    assert "The calibrated MKS cannot fly this launch" in view.messages.value
    assert set(_numbers(view.summary.value)) == {"3DOF"}  # the MKS's beta 1.2: not shown
    view.preset.value = "Chapter 2 A: HP"
    assert view.controls["calibrated_mks"].value  # a view the reader chose: kept
    assert "calibrated MKS" in _numbers(view.summary.value)


@pytest.mark.parametrize(
    "changes, says",
    [
        ({"elevation_deg": 10.0}, "Elevation (deg) must lie in [15, 88] deg; got 10 deg"),
        ({"speed_m_s": 3000.0}, "Muzzle speed (m/s) must lie in [1617.6, 2325.3] m/s; got 3000"),
        ({"density_change_percent": -15.0}, "Day's density (%) must lie in [-10, 10]; got -15"),
        (  # a custom round's band reaches 8.6 km/s: the 3DOF's flights would be cut short
            {"projectile": "custom", "drag_area_m2": 1e-4, "speed_m_s": 7500.0},
            "is not back on the ground within the 3DOF's 3000 s",
        ),
    ],
)
def test_the_calibrated_mks_refuses_what_its_table_does_not_cover_in_the_controls_words(
    changes, says
):
    """Outside its band the calibrated MKS is a message naming the control by its label and
    unit, before any table is learned (a table is never extrapolated); the rest still flies."""
    launch = explorer.launch_for(replace(explorer.preset("Chapter 2 A: HP"), **changes))
    looked_up = calibrated_mks._calibration.cache_info().misses
    flown, messages = explorer.fly(launch, ["3DOF", "MKS", "calibrated MKS"])
    assert calibrated_mks._calibration.cache_info().misses == looked_up  # nothing learned
    assert "calibrated MKS" not in flown and "3DOF" in flown
    refusal = [text for text in messages if text.startswith("The calibrated MKS cannot fly")]
    assert len(refusal) == 1 and says in refusal[0], messages
    assert not CODE_NAME.findall(refusal[0]), refusal


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    speed=st.floats(200, 4000),
    elevation=st.floats(1, 89.5),
    bearing=st.floats(0, 359),
    latitude=st.floats(-89, 89),
    rotating=st.booleans(),
    projectile=st.sampled_from(explorer.PROJECTILES),
)
def test_any_control_values_show_numbers_or_a_message(
    speed, elevation, bearing, latitude, rotating, projectile
):
    view = _fuzzed()
    for name, value in (
        ("projectile", projectile),
        ("speed_m_s", speed),
        ("elevation_deg", elevation),
        ("bearing_deg", bearing),
        ("latitude_deg", latitude),
        ("rotating", rotating),
    ):
        view.controls[name].value = value
    assert "3DOF" in view.summary.value or "cannot be flown" in view.messages.value
    assert math.isfinite(view.settings.speed_m_s)


@cache
def _fuzzed():
    return explorer.Explorer("Chapter 4 B: baseline, 45 deg")


def test_every_preset_is_a_launch():
    for name, setting in explorer.presets().items():
        assert isinstance(explorer.launch_for(setting), Launch), name


def _snapped(slider, value):
    """What a browser's slider shows of ``value`` and sends back: clamped to its range, on its
    grid of steps from its minimum."""
    held = min(max(value, slider.min), slider.max)
    return slider.min + round((held - slider.min) / slider.step) * slider.step


@pytest.mark.parametrize("name", ["HARP Barbados: round 181", "HARP Yuma: round 4"])
def test_a_preset_flies_as_named_whatever_its_sliders_show(name):
    """A browser's slider snaps the value it is given to its step and sends that back (44 of
    the 50 presets were changed so: Barbados round 181 flew 1798 m/s, not 1798.32, and lost
    its case and measured apogee). That echo must leave the launch as the preset names it."""
    setting = explorer.preset(name)
    view = explorer.Explorer(name)
    for field, slider in view.sliders.items():
        slider.value = _snapped(slider, getattr(setting, field))
    assert view.preset.value == name
    assert explorer.launch_for(view.settings) == explorer.launch_for(setting)
    assert view.settings.speed_m_s == setting.speed_m_s
    shown = _numbers(view.summary.value)
    if setting.measured_apogee_m is not None:
        assert shown["measured (HARP)"][0] == pytest.approx(setting.measured_apogee_m / 1e3)
    flown, _ = explorer.fly(explorer.launch_for(setting))
    assert shown["3DOF"][0] == pytest.approx(flown["3DOF"].apogee_m / 1e3, abs=5e-4)


def test_a_slider_moved_a_step_sets_its_box_and_a_typed_value_beyond_it_is_kept():
    view = explorer.Explorer("HARP Barbados: round 181")
    slider, box = view.sliders["speed_m_s"], view.controls["speed_m_s"]
    slider.value = _snapped(slider, box.value) + slider.step  # the reader's key press
    assert box.value == 1799.0 and view.settings.speed_m_s == 1799.0
    assert view.preset.value == "(your own)"
    box.value = 4321.5  # beyond the slider's 4000 m/s, which then sits at its end
    assert slider.value == slider.max
    assert view.settings.speed_m_s == 4321.5


def test_an_unknown_preset_is_named_with_the_known_ones():
    with pytest.raises(ValueError, match=r"no preset is called 'Chapter 9'.*Chapter 2 A: HP"):
        explorer.Explorer("Chapter 9")


# Code names: a snake_case word such as theta_rad, cross_wind_m_s or density_change_fraction.
CODE_NAME = re.compile(r"\b[a-z][a-z0-9]*_[a-z0-9_]+\b")


@pytest.mark.parametrize(
    "changes, label",
    [
        ({"elevation_deg": math.nan}, "Elevation (deg) must be finite; got nan"),
        ({"elevation_deg": 95.0}, "Elevation (deg) must lie in (0, 90] deg"),
        ({"speed_m_s": -5.0}, "Muzzle speed (m/s) must lie in (0, "),
        ({"speed_m_s": math.inf}, "Muzzle speed (m/s) must be finite"),
        ({"bearing_deg": math.nan}, "Bearing (deg T) must be finite"),
        ({"latitude_deg": 91.0}, "Latitude (deg) must lie in"),
        ({"cross_wind_m_s": 150.0}, "Cross wind (m/s) must lie in"),
        ({"head_wind_m_s": math.nan}, "Head wind (m/s) must be finite"),
        ({"density_change_percent": 60.0}, "Day's density (%) must lie in [-50, 50]; got 60"),
        ({"temperature_change_k": 99.0}, "Day's temperature (K) must lie in"),
        ({"spin_rad_s": math.inf}, "Spin (rad/s) must be finite"),
        ({"projectile": "Martlet", "mass_kg": -1.0}, "Mass (kg) must lie in (0, inf] kg"),
        ({"projectile": "custom", "drag_area_m2": math.nan}, "Cd0 A (m^2) must be finite"),
    ],
)
def test_bad_input_names_the_control_by_its_label_never_by_a_code_name(changes, label):
    with pytest.raises((ValueError, TypeError)) as error:
        explorer.launch_for(replace(explorer.presets()["Chapter 2 A: LP"], **changes))
    assert label in str(error.value)
    assert not CODE_NAME.findall(str(error.value)), str(error.value)


@pytest.mark.parametrize(
    "changes",
    [
        {"speed_m_s": 200.0, "elevation_deg": 1.0},  # no MKS: its closed form underflows
        {"speed_m_s": 9000.0, "elevation_deg": 89.5},  # the 3DOF's time limit
    ],
)
def test_the_engines_messages_reach_the_reader_without_code_names(changes):
    launch = explorer.launch_for(replace(explorer.presets()["Chapter 2 A: HP"], **changes))
    _, messages = explorer.fly(launch)
    assert len(messages) >= 2  # the wind's and the case's own
    assert not CODE_NAME.findall(" ".join(messages)), messages


def test_messages_shown_name_fields_by_their_labels_never_by_code_names():
    """The engines' warnings and refusals name the Launch's fields (launch.cross_wind_m_s,
    the day's density as a fraction): the page gives the control's label and unit."""
    view = explorer.Explorer("Chapter 2 A: LP")
    for name, value, says in (
        ("elevation_deg", math.nan, "This launch cannot be flown: Elevation (deg) must be"),
        ("elevation_deg", 45.0, '"Cross wind (m/s)" = 5'),  # a warning, flown
        ("density_change_percent", 3.0, None),
    ):
        view.controls[name].value = value
        shown = html.unescape(view.messages.value)
        assert says is None or says in shown, shown
        assert not CODE_NAME.findall(shown), shown
    view.rigid_body.click()  # Appendix B's rigid body leaves the day's air out
    assert '"Day\'s density (%)" = 3' in html.unescape(view.messages.value)
    view.controls["rotating"].value = True
    view.rigid_body.click()  # and cannot fly a rotating Earth
    shown = html.unescape(view.messages.value)
    assert 'cannot fly "the Earth\'s rotation (rad/s)" = 7.27' in shown, shown
    assert not CODE_NAME.findall(shown), shown


def test_cd0_a_is_shown_to_its_meaningful_digits():
    view = explorer.Explorer("Chapter 2 A: HP")
    for name in ("Chapter 2 A: HP", "Chapter 4 B: baseline, 45 deg", "HARP Yuma: round 4"):
        view.preset.value = name
        launch = explorer.launch_for(view.settings)
        exact = launch.launch_drag_coefficient * launch.projectile.reference_area_m2
        shown = view.controls["drag_area_m2"].value
        assert shown == float(f"{exact:.4g}"), (name, shown, exact)


def _served_settings(kernels: str):
    """serve/voila.py (what `make explore` gives Voila) run as traitlets runs a config file."""
    config = Config()
    path = Path(__file__).resolve().parents[1] / "serve" / "voila.py"
    environment = {"HARP_ANALYSIS_EXPLORER_KERNELS": kernels}
    with pytest.MonkeyPatch.context() as patch:
        for name, value in environment.items():
            patch.setenv(name, value)
        runpy.run_path(str(path), init_globals={"get_config": lambda: config})
    return config


def test_the_served_explorer_culls_idle_kernels_and_refuses_pages_beyond_its_cap():
    """Kernels live and starting (pending) count; at the cap a page gets a 503 with a
    sentence for the reader, below it the notebook goes on."""
    config = _served_settings("3")
    manager = config.MappingKernelManager
    assert manager.cull_idle_timeout > 0 and manager.cull_interval > 0
    assert manager.cull_connected is False  # a page left open keeps its kernel
    hook = config.VoilaConfiguration.prelaunch_hook

    class Manager:
        def __init__(self, live, pending):
            self._live, self._pending_kernels = live, dict.fromkeys(pending)

        def list_kernel_ids(self):
            return list(self._live)

    class Handler:
        def __init__(self, live, pending=()):
            self.kernel_manager = Manager(live, pending)

    notebook = object()
    assert hook(Handler(["a", "b"]), notebook=notebook, cwd=".") is notebook
    for live, pending in ((["a", "b", "c"], ()), (["a"], ["b", "c"])):
        with pytest.raises(HTTPError) as refused:
            hook(Handler(live, pending), notebook=notebook, cwd=".")
        assert refused.value.status_code == 503
        assert "The explorer is busy: 3 pages are open" in refused.value.reason
