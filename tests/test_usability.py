"""Calls take what users pass, and results say what they are.

One test per item: a misspelt scene field names the closest field (as the
kernel's reader does for a scene file), a Scene's repr lists what differs
from the defaults and remakes the scene, spectrum() takes a Trajectory, the
records of results show what matters in their repr, fourier_series returns a
named pair; and no guide page speaks of the machine it was written on.
"""

import math
import pathlib
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pendula

ROOT = pathlib.Path(__file__).resolve().parents[1]


# -- a misspelt field ---------------------------------------------------------

@pytest.mark.parametrize("call", [lambda: pendula.Scene(dampin=0.1), lambda: pendula.Scene().replace(dampin=0.1)],
                         ids=["constructor", "replace"])
def test_misspelt_field_is_a_scene_error_naming_the_closest(call):
    with pytest.raises(pendula.SceneError, match=r"unknown field 'dampin' \(did you mean 'damping'\?\)"):
        call()


TYPOS = ["colour", "dampin", "dampng", "v00", "thta0", "theta", "eps2", "drive_amplitud", "drivefrequency", "torq",
         "t_ned", "nsamples", "methd", "outputs_", "gravty", "restitusion", "cycloid_raduis", "x", "sweep_value",
         "grid_1"]


@pytest.mark.parametrize("word", TYPOS)
def test_misspelt_field_message_is_the_scene_file_readers(word):
    """difflib's suggestion in Python, the kernel's edit distance for files: the same answer on common slips."""
    with pytest.raises(pendula.SceneError) as from_file:
        pendula.Scene.from_namelist(f"&scene {word} = 1.0 /")
    with pytest.raises(pendula.SceneError) as from_python:
        pendula.Scene(**{word: 1.0})
    assert str(from_file.value).endswith(": " + str(from_python.value))


def test_unknown_field_far_from_every_name_has_no_suggestion():
    with pytest.raises(pendula.SceneError) as e:
        pendula.Scene(colour="red")
    assert str(e.value) == "unknown field 'colour'"


def test_unknown_field_is_still_a_value_error():
    with pytest.raises(ValueError):
        pendula.Scene(v00=1.0)


# -- Scene's repr ---------------------------------------------------------------

def test_scene_repr_lists_only_the_fields_that_differ():
    assert repr(pendula.Scene(v0=1.9)) == "Scene(v0=1.9)"
    assert repr(pendula.Scene()) == "Scene()"
    assert repr(pendula.Scene(v0=1.9, damping=0.1, outputs=("phase",))) == \
        "Scene(v0=1.9, damping=0.1, outputs=('phase',))"


def test_scene_repr_given_g_and_length_shows_them_not_eps():
    r = repr(pendula.Scene(g=9.81, length=2.0))
    assert r == "Scene(g=9.81, length=2.0)"


@settings(max_examples=40, deadline=None)
@given(v0=st.floats(-5, 5), damping=st.sampled_from([0.0, 0.1, 0.5]), eps=st.floats(0.1, 10),
       torque=st.floats(-1, 1), method=st.sampled_from(["auto", "dop853", "rk4"]))
def test_scene_repr_remakes_the_scene(v0, damping, eps, torque, method):
    s = pendula.Scene(v0=v0, damping=damping, eps=eps, torque=torque, method=method, dt=0.01)
    assert eval(repr(s), {"Scene": pendula.Scene}) == s


# -- spectrum of a Trajectory ------------------------------------------------

@pytest.fixture(scope="module")
def eight_periods():
    T = pendula.orbit(0.0, 1.9).period
    return T, pendula.simulate(pendula.Scene(v0=1.9), np.arange(4096) * (8 * T / 4096))


def test_spectrum_takes_a_trajectory(eight_periods):
    T, tr = eight_periods
    a, b, c = pendula.spectrum(tr), pendula.spectrum(tr.t, tr.theta), tr.spectrum()
    assert np.array_equal(a.power, b.power) and np.array_equal(a.power, c.power)
    # eight whole periods: the fundamental is 2 pi / T of the exact period, to rounding
    assert math.isclose(a.fundamental, 2 * math.pi / T, rel_tol=1e-13)


def test_spectrum_of_a_trajectory_takes_the_window(eight_periods):
    _, tr = eight_periods
    assert np.array_equal(tr.spectrum(window="hann").power, pendula.spectrum(tr.t, tr.theta, "hann").power)


def test_spectrum_without_the_signal_says_what_is_missing():
    with pytest.raises(TypeError, match="theta"):
        pendula.spectrum(np.arange(16.0))


def test_spectrum_of_a_trajectory_and_a_signal_is_refused(eight_periods):
    _, tr = eight_periods
    with pytest.raises(TypeError, match="Trajectory alone"):
        pendula.spectrum(tr, tr.theta)


# -- reprs of results ---------------------------------------------------------

def test_periodic_orbit_repr_shows_stable_period_and_kind():
    sc = pendula.Scene(damping=0.5, drive_amplitude=0.9, drive_frequency=2 / 3)
    po = pendula.periodic_orbit(sc, guess=(0.5, 0.5))
    r = repr(po)
    assert "stable=True" in r and "kind='oscillation'" in r
    assert f"period={po.period:.6g}" in r and math.isclose(po.period, 3 * math.pi, rel_tol=1e-15)
    assert "monodromy" not in r and len(r) < 200


def test_equilibrium_repr_shows_kind_and_stability():
    bottom, top = pendula.equilibria(pendula.Scene(damping=0.2))
    assert "kind='stable spiral'" in repr(bottom) and "stable=True" in repr(bottom)
    assert "kind='saddle'" in repr(top) and "stable=False" in repr(top)


def test_trajectory_repr_is_one_short_line():
    tr = pendula.simulate(pendula.Scene(v0=1.9, n_samples=5001))
    r = repr(tr)
    assert "\n" not in r and len(r) < 200
    assert "method='exact'" in r and "5001 samples" in r and "Scene(v0=1.9, n_samples=5001)" in r


def test_spectrum_repr_names_the_fundamental(eight_periods):
    T, tr = eight_periods
    r = repr(tr.spectrum())
    assert f"fundamental={2 * math.pi / T:.6g}" in r and len(r) < 120


def test_attractor_map_repr_names_the_attractors():
    sc = pendula.Scene(damping=0.5, drive_amplitude=1.35, drive_frequency=2 / 3)
    am = pendula.attractor_map(sc, {"theta0": [-2.0, 0.0, 2.0], "v0": [-3.0, 0.0, 3.0]}, transient=300,
                               samples=16)
    r = repr(am)
    assert "2 attractors" in r and r.count("periodic period 1") == 2 and len(r) < 300


# -- named results --------------------------------------------------------------

def test_fourier_series_is_named_and_unpacks_as_a_pair():
    fs = pendula.fourier_series(0.0, 1.9, 1.0, 4)
    omega, amps = fs
    assert isinstance(fs, pendula.FourierSeries)
    assert fs.omega == omega and fs.amplitudes is amps
    assert math.isclose(fs.omega, 2 * math.pi / pendula.orbit(0.0, 1.9).period, rel_tol=1e-15)


# -- the guide speaks to users --------------------------------------------------

GUIDE = sorted((ROOT / "docs" / "source" / "guide").glob("*.md")) + [ROOT / "docs" / "source" / "getting_started.rst"]
MACHINE = re.compile(r"shared machine|\b\d+-core\b|this machine|Measured \(|on the idle machine|niced", re.I)


@pytest.mark.parametrize("page", GUIDE, ids=[p.name for p in GUIDE])
def test_no_guide_page_mentions_the_machine(page):
    hits = [line for line in page.read_text().splitlines() if MACHINE.search(line)]
    assert hits == [], f"{page.name} speaks of the machine: {hits}"


@pytest.mark.parametrize("page", GUIDE, ids=[p.name for p in GUIDE])
def test_every_guide_page_has_one_title(page):
    text = re.sub(r"^```.*?^```", "", page.read_text(), flags=re.S | re.M)    # code blocks hold comments
    if page.suffix == ".md":
        titles = re.findall(r"^# \S", text, re.M)
    else:
        lines = text.splitlines()
        titles = [i for i in range(1, len(lines)) if re.fullmatch(r"=+", lines[i]) and lines[i - 1].strip()
                  and (i < 2 or not re.fullmatch(r"=+", lines[i - 2]))]
    assert len(titles) == 1, f"{page.name}: {len(titles)} titles"
