"""Bad and extreme input to equilibria and periodic_orbit, one test per class of cause
(docs/source/bad_input.rst): long work that Ctrl-C stops and a work limit bounds; extreme but valid
input that gives the right value or is refused; arguments through the one checker (no conversion)."""

import math
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import pendula
from pendula import Scene

DRIVE = Scene(damping=0.5, drive_amplitude=0.9, drive_frequency=2 / 3)


def _interrupted_within(code: str, wait: float, limit: float) -> float:
    """Run code in a child (SIGINT restored to its default), send SIGINT after `wait` s; the seconds the
    child took to stop after it (it must print 'interrupted')."""
    code = "import signal\nsignal.signal(signal.SIGINT, signal.default_int_handler)\n" + textwrap.dedent(code)
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        assert p.stdout.readline().strip() == "ready"
        time.sleep(wait)
        t0 = time.monotonic()
        p.send_signal(signal.SIGINT)
        out, _ = p.communicate(timeout=limit)
        assert "interrupted" in out
        return time.monotonic() - t0
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()


def test_long_work_is_interruptible_and_limited(monkeypatch):
    # a slow drive (a period of 6.3e6, within the time limit) stops on Ctrl-C: the monodromy flow polls
    code = """
        import pendula
        sc = pendula.Scene(damping=0.5, drive_amplitude=0.9, drive_frequency=1e-6)
        print("ready", flush=True)
        try:
            pendula.periodic_orbit(sc, guess=(0.5, 0.5))
        except KeyboardInterrupt:
            print("interrupted", flush=True)
    """
    assert _interrupted_within(code, 1.0, 10.0) < 5.0
    # a period beyond the time limit 1e8 is refused before any work
    t0 = time.monotonic()
    with pytest.raises(ValueError, match="drive_frequency"):
        pendula.periodic_orbit(DRIVE.replace(drive_frequency=1e-300), guess=(0.5, 0.5))
    # a flow that needs absurd work stops at the work limit (a ValueError, not a hang); the limit
    # lowered from 1e6 to 1e5 steps here to keep the test short (at 1e6 it takes about 6 s)
    from pendula.dynamics import periodic
    monkeypatch.setattr(periodic, "MAX_FLOW_STEPS", 10 ** 5)
    with pytest.raises(ValueError, match="work limit"):
        pendula.periodic_orbit(DRIVE.replace(torque=1e100), guess=(0.5, 0.5), maxit=1)
    # a window of angles beyond 2^52 (no fractional digits, an endless copy loop) is refused at once
    for window in ((1e17, 1e17 + 100), (2e16, 2e16 + 100)):
        with pytest.raises(ValueError, match="window"):
            pendula.equilibria(Scene(), window=window)
    assert time.monotonic() - t0 < 30


def test_extreme_valid_input_right_or_refused():
    # a guess beyond 2^52: one period moves theta by less than an ulp; refused
    with pytest.raises(ValueError, match="guess"):
        pendula.periodic_orbit(DRIVE, guess=(2.0 ** 60, 0.0))
    # a guess just inside, 2^50 + 0.5: reduced to one turn, the same orbit as from 0.5
    a = pendula.periodic_orbit(DRIVE, guess=(2.0 ** 50 + 0.5 - (2.0 ** 50) % (2 * math.pi), 0.5))
    b = pendula.periodic_orbit(DRIVE, guess=(0.5, 0.5))
    assert abs(math.remainder(a.theta - b.theta, 2 * math.pi)) < 1e-9 and abs(a.v - b.v) < 1e-9
    # the far inverse-square field is the uniform one: the top is a saddle with eigenvalues +-1
    eq = pendula.equilibria(Scene(gravity="inverse-square", gravity_distance=1e200))
    (top,) = [e for e in eq if abs(e.theta) > 3.0]
    assert top.kind == "saddle"
    np.testing.assert_allclose(sorted(top.eigenvalues.real), [-1.0, 1.0], rtol=1e-12)
    # heavy damping: lambda^2 + 1e200 lambda + 1 = 0 has -1e200 and -1e-200 (Vieta), a stable node
    (bottom,) = [e for e in pendula.equilibria(Scene(damping=1e200)) if abs(e.theta) < 1.0]
    lam = sorted(bottom.eigenvalues.real)
    assert bottom.kind == "stable node" and bottom.stable
    assert math.isclose(lam[0], -1e200, rel_tol=1e-15) and math.isclose(lam[1], -1e-200, rel_tol=1e-15)


@pytest.mark.parametrize("call, error", [
    (lambda: pendula.equilibria(Scene(), window=("0", "1")), TypeError),
    (lambda: pendula.equilibria(Scene(), window=(b"0", 1.0)), TypeError),
    (lambda: pendula.equilibria(Scene(), window=(False, 1.0)), TypeError),
    (lambda: pendula.equilibria(Scene(), window=(0, 10 ** 400)), ValueError),
    (lambda: pendula.periodic_orbit(DRIVE, guess=("0.5", "0.5")), TypeError),
    (lambda: pendula.periodic_orbit(DRIVE, guess=(True, False)), TypeError),
    (lambda: pendula.periodic_orbit(DRIVE, guess=(10 ** 400, 0)), ValueError),
    (lambda: pendula.periodic_orbit(DRIVE, guess=(0.5, 0.5), tol=True), TypeError),
    (lambda: pendula.periodic_orbit(DRIVE, guess=(0.5, 0.5), rtol=1.0), ValueError),
    (lambda: pendula.periodic_orbit(DRIVE, guess=(0.5, 0.5), k=2.0), TypeError),
    (lambda: pendula.continue_orbit(DRIVE, (0.5, 0.5), "damping", "0.6"), TypeError),
    (lambda: pendula.continue_orbit(DRIVE, (0.5, 0.5), "damping", 0.6, step=True), TypeError),
    (lambda: pendula.continue_equilibria(Scene(), "torque", 0.5, points=3.0), TypeError),
])
def test_dynamics_arguments_through_the_checker(call, error):
    # the one checker's verdicts: no string, bytes or bool converted; out of range a ValueError
    with pytest.raises(error):
        call()
