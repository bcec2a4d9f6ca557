"""Scene files of the systems built by their own class, through pendula-run.

A file whose namelist group is ``&double``, ``&foucault`` or ``&network`` is
that system's scene: its fields are read and checked beside the system in the
kernel (kernel/dispatch/pendula_double_scene.f90, pendula_foucault_scene.f90,
pendula_network_scene.f90), a malformed field gives exit 2 naming the field,
and the run goes through the same n-dimensional driver as
``pendula.DoublePendulum``, ``pendula.FoucaultPendulum`` and
``pendula.Network``: the same numbers to the bit.
"""

import math
import subprocess

import numpy as np
import pytest

import pendula

from conftest import DATA, venv_bin


def _run(*args):
    return subprocess.run([venv_bin("pendula-run"), *map(str, args)], capture_output=True, text=True)


def _table(text):
    return np.array([[float(x) for x in ln.split(",")] for ln in text.splitlines() if ln and ln[0] not in "#t"])


def test_double_pendulum_scene_runs_and_keeps_the_closed_form_energy(tmp_path):
    """The example scene: released from rest at (2, 1), so the energy is V(2, 1) = 2 (1 - cos 2) + (1 - cos 1)
    (g = l = m = 1, closed form).  Gauss-Legendre 6 is symplectic: with dt = 0.01 its energy error stays
    bounded at O(dt^6) = 1e-12 (relative; measured 1.0e-12) over the whole chaotic run."""
    out = tmp_path / "double.csv"
    p = _run(DATA / "scenes" / "systems" / "double_pendulum.nml", "-o", out)
    assert p.returncode == 0, p.stderr
    text = out.read_text()
    assert "t,theta1,theta2,omega1,omega2,energy" in text and "method gauss6" in text
    d = _table(text)
    assert d.shape == (201, 6)
    np.testing.assert_array_equal(d[:, 0], np.linspace(0.0, 20.0, 201))
    e0 = 2.0 * (1.0 - math.cos(2.0)) + (1.0 - math.cos(1.0))
    err = np.abs(d[:, 5] - e0) / e0
    assert err[0] <= 2 * np.finfo(float).eps and err.max() <= 1e-11


def test_double_pendulum_scene_is_the_class_path_to_the_bit(tmp_path):
    """The scene file and pendula.DoublePendulum run the same kernel path (nd_run): the same numbers."""
    f = tmp_path / "s.nml"
    f.write_text("&double\n m1 = 1.5, m2 = 0.7, l1 = 1.2, l2 = 0.8, g = 1.0, rods = .true., damping = 0.05, 0.02\n"
                 " theta1 = 1.1, theta2 = -0.4, omega1 = 0.3, omega2 = -0.2\n"
                 " t_end = 5.0, n_samples = 11, method = 'dop853', rtol = 1e-11, atol = 1e-11\n/\n")
    p = _run(f)
    assert p.returncode == 0, p.stderr
    d = _table(p.stdout)
    dp = pendula.DoublePendulum(m1=1.5, m2=0.7, l1=1.2, l2=0.8, g=1.0, rods=True, damping=[0.05, 0.02])
    run = dp.simulate(np.linspace(0, 5, 11), theta1=1.1, theta2=-0.4, omega1=0.3, omega2=-0.2, method="dop853",
                      rtol=1e-11, atol=1e-11)
    for k, name in enumerate(("theta1", "theta2", "omega1", "omega2", "energy"), start=1):
        np.testing.assert_array_equal(d[:, k], run[name].values, err_msg=name)


@pytest.mark.parametrize("body, field", [
    ("m1 = -1.0", "m1"), ("l2 = 0.0", "l2"), ("g = -9.8", "g"), ("damping = -0.1, 0.0", "damping"),
    ("t_end = -1.0", "t_end"), ("n_samples = 0", "n_samples"), ("method = 'rk4'", "method"),
    ("method = 'gauss6', dt = 0.03, t_end = 1.0, n_samples = 11", "dt"), ("rtol = 0.0", "rtol"),
    ("mass = 1.0", "mass"), ("theta1 = abc", "theta1"), ("n_samples = 1.5", "n_samples"), ("rods = 3", "rods"),
    ("g = 1.0, theta2 = 'x'", "theta2"),
])
def test_double_pendulum_scene_refuses_a_malformed_field_by_name(tmp_path, body, field):
    f = tmp_path / "bad.nml"
    f.write_text(f"&double\n {body}\n/\n")
    out = tmp_path / "o.csv"
    for args in ((f, "-o", out), (f, "--check")):
        p = _run(*args)
        assert p.returncode == 2, (body, p.stdout)
        assert field in p.stderr and "&double" in p.stderr, p.stderr
    assert not out.exists()


def test_foucault_scene_runs_on_its_sphere_and_is_the_class_path_to_the_bit(tmp_path):
    """The example scene (Paris, 67 m): the bob stays on the sphere of radius length (a closed-form
    invariant, to 1e-9 relative at rtol 1e-12), and the numbers are those of pendula.FoucaultPendulum."""
    out = tmp_path / "f.csv"
    p = _run(DATA / "scenes" / "systems" / "foucault_paris.nml", "-o", out)
    assert p.returncode == 0, p.stderr
    text = out.read_text()
    assert "t,x,y,z,vx,vy,vz" in text
    d = _table(text)
    assert d.shape == (601, 7)
    assert np.max(np.abs(np.sqrt(d[:, 1] ** 2 + d[:, 2] ** 2 + d[:, 3] ** 2) / 67.0 - 1.0)) < 1e-9
    run = pendula.FoucaultPendulum(latitude=48.85, length=67.0, g=9.81).simulate(np.linspace(0, 600, 601), 0.05,
                                                                                 rtol=1e-12)
    for k, name in enumerate(("x", "y", "z", "vx", "vy", "vz"), start=1):
        np.testing.assert_array_equal(d[:, k], run[name].values, err_msg=name)


@pytest.mark.parametrize("body, field", [
    ("latitude = 100.0", "latitude"), ("length = -1.0", "length"), ("damping = -0.1", "damping"),
    ("anisotropy = -2.0, 0.0", "anisotropy"), ("theta0 = 2.0", "theta0"), ("theta0 = 0.0, phi_dot0 = 0.1", "phi_dot0"),
    ("t_end = 0.0", "t_end"), ("n_samples = 0", "n_samples"), ("rtol = 0.0", "rtol"), ("lat = 45.0", "lat"),
    ("theta0 = x", "theta0"),
])
def test_foucault_scene_refuses_a_malformed_field_by_name(tmp_path, body, field):
    f = tmp_path / "bad.nml"
    f.write_text(f"&foucault\n latitude = 45.0\n {body}\n/\n")
    p = _run(f, "--check")
    assert p.returncode == 2 and f"'{field}'" in p.stderr and "&foucault" in p.stderr, p.stderr


def test_network_scene_is_the_class_path_to_the_bit_and_conserves_energy(tmp_path):
    """The example chain of four: the numbers of pendula.Network on the same times; and without damping
    the energy (closed form: sum of C v^2 / 2 + eps (1 - cos phi) + K (dphi)^2 / 2) stays at its start,
    E0 = 1 - cos 0.5 + 0.5 * 0.5^2 / 2, to 1e-9 relative at rtol 1e-10 (DOP853's error per unit time)."""
    out = tmp_path / "n.csv"
    p = _run(DATA / "scenes" / "systems" / "network_chain.nml", "-o", out)
    assert p.returncode == 0, p.stderr
    d = _table(out.read_text())
    assert d.shape == (401, 9)
    net = pendula.Network(4, topology="chain", strength=0.5, damping=0.02)
    run = net.simulate(np.linspace(0, 40, 401), phi0=[0.5, 0.0, 0.0, 0.0], rtol=1e-10, atol=1e-12)
    np.testing.assert_array_equal(d[:, 1:5], run.phi.values)
    np.testing.assert_array_equal(d[:, 5:9], run.v.values)
    f = tmp_path / "ring.nml"
    f.write_text("&network\n n = 5, topology = 'ring', strength = 0.3, phi0 = 0.8, 0.0, 0.0, 0.0, -0.4\n"
                 " t_end = 20.0, n_samples = 21, method = 'gauss6', dt = 0.01\n/\n")
    p = _run(f)
    assert p.returncode == 0, p.stderr
    d = _table(p.stdout)
    phi, v = d[:, 1:6], d[:, 6:11]
    dphi = np.roll(phi, -1, axis=1) - phi           # the ring's five springs, each once
    en = (0.5 * v ** 2 + (1 - np.cos(phi))).sum(axis=1) + 0.5 * 0.3 * (dphi ** 2).sum(axis=1)
    e0 = (1 - math.cos(0.8)) + (1 - math.cos(-0.4)) + 0.5 * 0.3 * (0.8 ** 2 + 0.4 ** 2 + 1.2 ** 2)
    assert abs(en[0] - e0) <= 4 * np.finfo(float).eps * e0
    assert np.max(np.abs(en - e0)) / e0 < 1e-9


@pytest.mark.parametrize("body, field", [
    ("n = 0", "n"), ("n = 3, mass = 1.0, 2.0", "mass"), ("mass = 0.0", "mass"), ("damping = -1.0", "damping"),
    ("topology = 'star'", "topology"), ("n = 3, topology = 'pair'", "topology"), ("strength = -1.0", "strength"),
    ("method = 'rk4'", "method"), ("method = 'gauss6', dt = 0.03, t_end = 1.0, n_samples = 11", "dt"),
    ("phi0 = x", "phi0"), ("coupling = 1.0", "coupling"), ("t_end = -1.0", "t_end"),
])
def test_network_scene_refuses_a_malformed_field_by_name(tmp_path, body, field):
    f = tmp_path / "bad.nml"
    f.write_text(f"&network\n {body}\n/\n")
    p = _run(f, "--check")
    assert p.returncode == 2 and f"'{field}'" in p.stderr and "&network" in p.stderr, p.stderr
