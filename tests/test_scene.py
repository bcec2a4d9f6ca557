"""Scenes: the namelist format (one reader: the kernel's, for Python and the
Fortran executable), checks that name the field, method selection, and the
pendula-run executable."""

import subprocess

import numpy as np
import pytest

import pendula
from pendula import Scene, SceneError
from conftest import EPS, venv_bin

GOOD = """! a comment before the group
&scene
  name = 'near the separatrix'   ! trailing comment
  eps = 1.0, theta0 = 0.0
  v0 = 1.9
  t_start = -1.0, t_end = 3.0, n_samples = 9
  outputs = 'trajectory', 'period'
  sweep = 'v0', sweep_values = 1.5, 1.9 2.5
/
"""


def test_namelist_round_trip():
    s = Scene.from_namelist(GOOD)
    assert s.v0 == 1.9 and s.sweep_values == (1.5, 1.9, 2.5) and s.n_samples == 9
    assert s.outputs == ("trajectory", "period") and s.name == "near the separatrix"
    assert Scene.from_namelist(s.to_namelist()) == s


def test_g_and_length_give_eps():
    s = Scene(g=9.81, length=2.0)
    assert s.eps == 9.81 / 2.0
    with pytest.raises(SceneError, match="'g' and 'length'"):
        Scene(g=9.81)


@pytest.mark.parametrize("text,field", [
    ("&scene vv0 = 1.0 /", "unknown field 'vv0'"),
    ("&scene v0 = 'fast' /", "field 'v0' must be a real number"),
    ("&scene eps = -1.0 /", "field 'eps' must be positive"),
    ("&scene n_samples = 2.5 /", "field 'n_samples' must be a whole number"),
    ("&scene method = 'rk5' /", "field 'method'"),
    ("&scene outputs = 'thetta_t' /", "did you mean 'theta_t'"),
    ("&scene sweep = 'v0' /", "field 'sweep_values' is empty"),
    ("&scene damping = -0.1 /", "field 'damping' must be >= 0"),
    ("&scene v0 = 1.0, v0 = 2.0 /", "field 'v0' is given twice"),
    ("&scene v0 = 1.0", "not closed"),
    ("&other v0 = 1.0 /", "must start with the group '&scene'"),
    ("&scene method = 'exact', damping = 0.1 /", "field 'method'"),
])
def test_malformed_scenes_name_the_field(text, field):
    with pytest.raises(SceneError, match=field.replace("(", r"\(").replace(")", r"\)")):
        Scene.from_namelist(text)


def test_python_constructor_validates_too():
    with pytest.raises(SceneError, match="'theta0'"):
        Scene(theta0="a")
    with pytest.raises(SceneError, match="'theta0' must be finite"):
        Scene(theta0=np.inf)


def test_conservative_scene_is_answered_exactly():
    s = Scene(v0=1.5, t_start=3.0, t_end=-3.0, n_samples=7)
    tr = pendula.simulate(s)
    assert tr.method == "exact" and tr.t[0] == 3.0 and tr.t[-1] == -3.0
    theta, v = pendula.exact_motion(0.0, 1.5, 1.0, tr.t)
    assert np.array_equal(theta, tr.theta) and np.array_equal(v, tr.v)
    assert np.abs(tr.energy - 1.125).max() <= 4 * EPS
    assert pendula.period(s) == pendula.orbit(0.0, 1.5).period


def test_effects_are_named_only_when_given():
    assert Scene().effects == ()
    assert Scene(damping=0.1, torque=0.2).effects == ("damping", "torque")
    assert Scene(drive_amplitude=0.5, drive_frequency=1.0).effects == ("drive",)
    with pytest.raises(ValueError, match="period"):
        pendula.period(Scene(damping=0.1))


def test_every_registered_model_runs_and_two_models_at_once_are_refused():
    # every model the scene format names is implemented now (pendula.models())
    assert all(m.implemented for m in pendula.models())
    with pytest.raises(ValueError, match="cord|guide"):
        pendula.simulate(Scene(guide="cycloid", cord="flexible"))


def test_members_of_a_sweep():
    s = Scene.from_namelist(GOOD)
    assert [m.v0 for m in s.members()] == [1.5, 1.9, 2.5]
    assert all(m.sweep == "" for m in s.members())


# ---------------------------------------------------------------- pendula-run

def run(*args):
    return subprocess.run([venv_bin("pendula-run"), *args], capture_output=True, text=True)


def test_pendula_run_matches_python(tmp_path):
    f = tmp_path / "s.nml"
    f.write_text(GOOD)
    out = tmp_path / "out.csv"
    p = run(str(f), "-o", str(out))
    assert p.returncode == 0, p.stderr
    lines = out.read_text().splitlines()
    assert lines[0].startswith("# pendula-run") and any("v0 =" in ln for ln in lines[:8])
    data = np.array([[float(x) for x in ln.split(",")] for ln in lines if ln and not ln[0] in "#v"])
    assert data.shape == (27, 5)
    for value in (1.5, 1.9, 2.5):
        rows = data[data[:, 0] == value]
        theta, v = pendula.exact_motion(0.0, value, 1.0, rows[:, 1])
        assert np.abs(rows[:, 2] - theta).max() <= 2 * EPS * max(1, np.abs(theta).max())
        assert np.abs(rows[:, 3] - v).max() <= 2 * EPS * 3
    orbits = (tmp_path / "out_orbits.csv").read_text().splitlines()
    assert "period" in orbits[orbits.index(next(ln for ln in orbits if ln.startswith("theta0")))]
    per = [float(ln.split(",")[5]) for ln in orbits if ln and ln[0] not in "#t"]
    assert per == pytest.approx([pendula.orbit(0, v).period for v in (1.5, 1.9, 2.5)], rel=2 * EPS)


@pytest.mark.parametrize("text,what", [
    ("&scene\n eps = 1.0\n vv0 = 3\n/\n", "line 3: unknown field 'vv0'"),
    ("&scene\n v0 = 'abc'\n/\n", "line 2: field 'v0' must be a real number, got 'abc'"),
    ("&scene\n eps = -1.0\n/\n", "field 'eps' must be positive"),
    ("&scene\n method = 'rk5'\n/\n", "field 'method'"),
    ("&scene\n sweep = 'v0'\n/\n", "field 'sweep_values' is empty"),
    ("&scene\n v0 = 1.0\n", "not closed"),
])
def test_pendula_run_rejects_bad_scenes_without_output(tmp_path, text, what):
    f = tmp_path / "bad.nml"
    f.write_text(text)
    out = tmp_path / "out.csv"
    p = run(str(f), "-o", str(out))
    assert p.returncode == 2
    assert what in p.stderr
    assert not out.exists()


def test_pendula_run_missing_file(tmp_path):
    p = run(str(tmp_path / "nope.nml"))
    assert p.returncode == 2 and "cannot read" in p.stderr


def test_gallery_scenes_parse_in_python_and_fortran(tmp_path, data_dir):
    # the flexible-cord scenes (cord_*.nml) are single runs, not sweeps: tests/test_cord.py runs them
    # in Python and through pendula-run
    scenes = sorted(p for p in (data_dir / "scenes").glob("*.nml") if not p.name.startswith("cord_"))
    assert len(scenes) >= 8
    for f in scenes:
        s = Scene.from_file(f)
        p = run(str(f), "-o", str(tmp_path / (f.stem + ".csv")))
        assert p.returncode == 0, (f.name, p.stderr)
        assert s.sweep and len(s.sweep_values) >= 2


def test_pendula_run_integrates_scenes_with_effects(tmp_path):
    """The compiled runner picks the same integrator for a damped scene under 'auto' as the Python
    layer (the kernel's table) and agrees with it (same kernel, same tolerances: to rounding)."""
    f = tmp_path / "damped.nml"
    f.write_text("&scene\n v0 = 2.3, damping = 0.04, t_end = 50.0, n_samples = 11\n"
                 " rtol = 1e-11, atol = 1e-13\n/\n")
    out = tmp_path / "d.csv"
    p = run(str(f), "-o", str(out))
    assert p.returncode == 0, p.stderr
    text = out.read_text()
    data = np.array([[float(x) for x in ln.split(",")] for ln in text.splitlines() if ln and ln[0] not in "#t"])
    tr = pendula.simulate(Scene.from_file(f))
    assert "# effects = damping" in text and f"# solver = {tr.method} (method auto" in text
    assert tr.method in ("dop853", "vern9", "vern8")
    assert np.abs(data[:, 1] - tr.theta).max() < 1e-12 and np.abs(data[:, 2] - tr.v).max() < 1e-12


def test_fixed_step_method_without_dt_is_a_bad_scene_in_both_programs(tmp_path):
    f = tmp_path / "rk.nml"
    f.write_text("&scene\n v0 = 1.0, damping = 0.1, method = 'rk4'\n/\n")
    p = run(str(f), "-o", str(tmp_path / "o.csv"))
    assert p.returncode == 2 and "field 'dt'" in p.stderr
    with pytest.raises(SceneError) as exc:
        Scene.from_file(f)
    assert p.stderr.strip() == "pendula-run: " + str(exc.value)


def test_cli_run_writes_tables_and_figures(tmp_path, data_dir):
    from pendula.cli import main
    assert main(["run", str(data_dir / "scenes" / "fig10_theta_max_vs_v0.nml"), "-o", str(tmp_path), "-q"]) == 0
    assert (tmp_path / "fig10_theta_max_vs_v0_orbits.csv").exists()
    assert (tmp_path / "fig10_theta_max_vs_v0_orbits.png").stat().st_size > 10_000
    bad = tmp_path / "bad.nml"
    bad.write_text("&scene vv0 = 1 /")
    assert main(["run", str(bad), "-o", str(tmp_path)]) == 2


def test_run_trajectory_csv_round_trips(tmp_path):
    """The CSV holds every digit: read back, it is the exact motion bit for bit."""
    from pendula.run import run_scene
    s = Scene.from_namelist(GOOD).replace(outputs=("trajectory",))
    (path,) = run_scene(s, tmp_path, stem="t", progress=False)
    lines = [ln for ln in path.read_text().splitlines() if not ln.startswith("#")]
    assert lines[0] == "v0,t,theta,v,energy"
    data = np.array([[float(x) for x in ln.split(",")] for ln in lines[1:]])
    assert data.shape == (27, 5)
    for value in (1.5, 1.9, 2.5):
        rows = data[data[:, 0] == value]
        theta, v = pendula.exact_motion(0.0, value, 1.0, rows[:, 1])
        assert np.array_equal(rows[:, 2], theta) and np.array_equal(rows[:, 3], v)


# ------------------------------------------- one verdict from both programs

def one_verdict(tmp_path, capsys, text: str) -> tuple[int, str]:
    """Run a scene file through pendula-run and `pendula run`; both must give
    the same exit status and (after the program's name) the same message."""
    from pendula.cli import main

    f = tmp_path / "case.nml"
    f.write_text(text)
    p = run(str(f), "-o", str(tmp_path / "native.csv"))
    capsys.readouterr()
    code = main(["run", str(f), "-o", str(tmp_path / "py"), "-q"])
    err = capsys.readouterr().err.strip()
    assert code == p.returncode, (code, err, p.returncode, p.stderr)
    native_msg = p.stderr.strip().removeprefix("pendula-run: ")
    assert err.removeprefix("pendula run: ") == native_msg
    return code, native_msg


def test_spectrum_on_the_separatrix_is_refused_by_both_programs(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene  v0 = 2.0, outputs = 'trajectory', 'spectrum', "
                                              "t_end = 5.0, n_samples = 11 /\n")
    assert code == 2 and "field 'outputs'" in msg and "separatrix has no spectrum" in msg


def test_series_without_an_amplitude_sweep_is_refused_by_both_programs(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene  v0 = 1.0, outputs = 'trajectory', 'series', "
                                              "t_end = 5.0, n_samples = 11 /\n")
    assert code == 2 and "sweep theta0 with v0 = 0" in msg


def test_lindstedt_amplitude_beyond_pi_is_refused_by_both_programs(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene  v0 = 0.0, outputs = 'trajectory', 'lindstedt', "
                                              "sweep = 'theta0', sweep_values = 0.5, 4.0 /\n")
    assert code == 2 and "theta0 = 4.0" in msg and "|theta0| < pi" in msg


def test_atol_overflowing_to_infinity_is_refused_by_both_programs(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene\n  atol = 1d999\n/\n")
    assert code == 2 and "field 'atol' must be finite" in msg


def test_repeat_count_without_its_value_is_refused_by_both_programs(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene\n  grid = 'v0', 'theta0', measure = 'locked'\n"
                                              "  grid1 = 1.0, 2.0\n  grid2 = 3*\n/\n")
    assert code == 2 and "line 4: field 'grid2'" in msg and "repeat count" in msg


def test_empty_grid_axis_name_is_refused_by_both_programs(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene\n  grid = ''\n/\n")
    assert code == 2 and "field 'grid': cannot sweep ''" in msg


def test_empty_output_name_is_refused_by_both_programs(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene\n  outputs = ''\n/\n")
    assert code == 2 and "field 'outputs': unknown output ''" in msg


def test_theta0_1e308_without_a_sweep_is_refused_naming_theta0(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene\n  theta0 = 1e308\n/\n")
    assert code == 2 and "field 'theta0'" in msg and "2^52" in msg and "sweep" not in msg


def test_grid1_with_4097_values_is_refused_naming_the_limit(tmp_path, capsys):
    values = ", ".join(f"{1 + k * 1e-4:.4f}" for k in range(4097))
    code, msg = one_verdict(tmp_path, capsys, f"&scene\n  grid = 'v0', measure = 'locked'\n  grid1 = {values}\n/\n")
    assert code == 2 and "line 3: field 'grid1' holds at most 4096 values, got 4097" in msg


def test_theta0_with_5000_digits_is_refused_naming_theta0(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene\n  theta0 = " + "7" * 5000 + ".0\n/\n")
    assert code == 2 and "field 'theta0' must be finite" in msg


def test_period_of_a_damped_scene_is_refused_by_both_programs(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene\n  v0 = 1.0, damping = 0.1, outputs = 'period'\n/\n")
    assert code == 2 and "period/omega/theta_max" in msg and "damping" in msg


def test_conservative_cycloid_orbit_facts_are_given_by_both_programs(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene\n  guide = 'cycloid', theta0 = 0.5, outputs = 'period'\n/\n")
    assert code == 0 and msg == ""


def test_did_you_mean_names_the_closest_field_and_word():
    with pytest.raises(SceneError, match=r"line 2: unknown field 'dampin' \(did you mean 'damping'\?\)"):
        Scene.from_namelist("&scene\n dampin = 0.1\n/\n")
    with pytest.raises(SceneError, match=r"got 'dop835' \(did you mean 'dop853'\?\)"):
        Scene(method="dop835")
    with pytest.raises(SceneError, match=r"got 'lockd' \(did you mean 'locked'\?\)"):
        Scene(grid=("v0",), grid1=(1.0,), measure="lockd")


def test_fields_and_text_are_checked_by_the_same_rules():
    text_err = fields_err = None
    try:
        Scene.from_namelist("&scene guide = 'cycloid', theta0 = 1.7 /")
    except SceneError as exc:
        text_err = str(exc)
    try:
        Scene(guide="cycloid", theta0=1.7)
    except SceneError as exc:
        fields_err = str(exc)
    assert text_err == "<scene>, line 1: " + fields_err and "cusps" in fields_err


def test_replace_is_checked_on_the_fields():
    s = Scene(v0=1.0)
    with pytest.raises(SceneError, match="field 'outputs'.*separatrix"):
        s.replace(v0=2.0, outputs=("spectrum",))
    assert s.replace(method="DOPRI5").method == "dopri5"


def test_conservative_cycloid_orbit_beyond_the_cusps_is_refused_by_both_programs(tmp_path, capsys):
    code, msg = one_verdict(tmp_path, capsys, "&scene\n  guide = 'cycloid', theta0 = 1.5, v0 = 2.0, "
                                              "outputs = 'period'\n/\n")
    assert code == 2 and "field 'v0'" in msg and "cusps" in msg
    with pytest.raises(SceneError, match="cusps"):
        pendula.period(Scene(guide="cycloid", v0=10.0))


def test_range_errors_name_the_line_of_the_field():
    with pytest.raises(SceneError, match=r"^<scene>, line 3: field 'damping' must be >= 0, got -0.1$"):
        Scene.from_namelist("&scene\n v0 = 1.0\n damping = -0.1\n/\n")
    with pytest.raises(SceneError, match=r"^<scene>, line 2: field 'sweep_values': eps = 0.0: field 'eps' must be"):
        Scene.from_namelist("&scene\n sweep = 'eps', sweep_values = 1.0, 0.0\n/\n")
    # a rule on a field the text does not give: no line to name
    with pytest.raises(SceneError, match=r"^<scene>: field 'sweep_values' is empty but 'sweep' names a field$"):
        Scene.from_namelist("&scene\n sweep = 'v0'\n/\n")


def test_a_run_beyond_the_work_limit_fails_alike_in_both_programs(tmp_path, capsys):
    # a failure of the computation (exit 4), not of the scene: the dispatcher's one message
    code, msg = one_verdict(tmp_path, capsys, "&scene\n  v0 = 1.0, damping = 0.1, method = 'rk4', dt = 1e-9, "
                                              "t_end = 1000.0, n_samples = 3\n/\n")
    assert code == 4 and "more steps than the work limit" in msg


def test_gsl_rk8pd_in_a_gravity_field_is_a_bad_scene_naming_the_method():
    with pytest.raises(SceneError, match="field 'method': gsl-rk8pd does not take a non-uniform gravity"):
        Scene(gravity="linear", gravity_gradient=0.1, method="gsl-rk8pd")
