"""Periodic orbits of a driven scene: Newton on the stroboscopic map and its monodromy.

The flow and its monodromy matrix (the variational equations) run in the
kernel (GSL's rk8pd, ``kernel/glue/pendula_gsl.c``, stepped there so that it
polls the cancel flag and stops at a work limit); Newton's iteration on the
map runs here.  This module is the one Newton-and-monodromy core of the
dynamics: :func:`periodic_orbit` is Newton at a fixed parameter, and the
continuation (:mod:`.continuation`) is the same Newton with the parameter as
one more unknown and one more (pseudo-arclength) equation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .. import _checks, _interrupt, _kernel
from ..scene import Scene, SceneError
from ..systems import contract

__all__ = ["PeriodicOrbit", "periodic_orbit"]


@dataclass(frozen=True)
class PeriodicOrbit:
    """A periodic orbit of a driven scene's stroboscopic map.

    Attributes
    ----------
    theta, v : float
        The orbit's state on the section ``t = 0 (mod period)`` (the drive's phase ``drive_phase``),
        theta in ``[-pi, pi]``.  A period-k call may find an orbit of a smaller period that divides k.
    period : float
        Its period, ``k`` drive periods ``2 pi k / drive_frequency``.
    multipliers : numpy.ndarray
        The Floquet multipliers (the eigenvalues of the monodromy matrix), largest modulus first.
    exponents : numpy.ndarray
        ``log|mu| / period``, the Lyapunov exponents of the orbit; they add up to ``-damping``.
    monodromy : numpy.ndarray
        The 2 x 2 monodromy matrix ``d(theta, v)(period) / d(theta, v)(0)``.
    winding : int
        Turns the orbit advances per period (0 for an oscillation).
    kind : str
        'oscillation' or 'rotation' (from the winding).
    stable : bool
        True when every multiplier lies inside the unit circle.
    residual : float
        ``max |P(x) - x - (2 pi winding, 0)|`` at the returned state.
    det_residual : float
        The certificate of the multipliers: ``abs(det M - exp(-damping period))`` (Liouville's formula:
        the flow shrinks areas at the rate ``damping``), about the integrator's tolerance times
        ``(1 + norm(M))^2``; NaN with drag or a user's force (their rate is not constant).
    multiplier_error : float
        The bound on the error of ``tr M`` and ``det M`` from the flow's tolerance,
        ``100 rtol (1 + norm(M))^2`` (measured below 0.22 of it on random orbits against flows at 1e-15).
    certified : bool
        True when the stability verdict is decided beyond that error (by the Jury conditions
        ``1 - tr M + det M``, ``1 + tr M + det M``, ``1 - det M``: all above it for a stable orbit, one
        below minus it for an unstable one) and the Liouville residual lies within it: the verdict
        then does not depend on the integrator's tolerance.  False next to a bifurcation.

    See Also
    --------
    periodic_orbit : makes it.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=0.9, drive_frequency=2/3)
    >>> po = pendula.periodic_orbit(sc, guess=(0.5, 0.5))
    >>> round(float(po.exponents.sum()), 9)          # Liouville: -damping
    -0.5
    >>> po                       # a complex pair: |mu| = exp(-damping * period / 2)
    PeriodicOrbit(theta=-0.560228, v=1.93359, period=9.42478, kind='oscillation', stable=True, |multipliers|=[0.09478, 0.09478])
    """

    theta: float
    v: float
    period: float
    multipliers: np.ndarray
    exponents: np.ndarray
    monodromy: np.ndarray
    winding: int
    residual: float
    det_residual: float = math.nan
    multiplier_error: float = math.nan
    certified: bool = False

    @property
    def stable(self) -> bool:
        """True when every multiplier lies inside the unit circle."""
        return bool(np.all(np.abs(self.multipliers) < 1))

    @property
    def kind(self) -> str:
        """'oscillation' (winding 0) or 'rotation' (the orbit advances ``winding`` turns per period)."""
        return "oscillation" if self.winding == 0 else "rotation"

    def __repr__(self) -> str:
        mods = ", ".join(f"{abs(m):.4g}" for m in self.multipliers)
        wind = f", winding={self.winding}" if self.winding else ""
        return (f"PeriodicOrbit(theta={self.theta:.6g}, v={self.v:.6g}, period={self.period:.6g}, "
                f"kind={self.kind!r}{wind}, stable={self.stable}, |multipliers|=[{mods}])")


#: The work limit of one flow: at most max(MAX_FLOW_STEPS, STEPS_PER_TIME * |t|) rk8pd steps over a time t
#: (a period of the driven pendulum takes a few hundred; 1000 per unit time is a hundred times what a
#: pendulum with frequencies near 1 needs).
MAX_FLOW_STEPS = 10**6
STEPS_PER_TIME = 1000
#: Flows up to this many steps (tens of milliseconds) run without the interruptible worker thread.
_DIRECT_STEPS = 20_000

_FLOW_STATUS = {1: "the flow failed (the state left the finite numbers, or rk8pd could not meet its tolerance)",
                2: f"the flow needed more than max({MAX_FLOW_STEPS:.0e}, {STEPS_PER_TIME} t) steps (the work limit)",
                100: "the scene's fields were refused by the kernel"}


class FlowError(ValueError):
    """The flow over a period failed or exceeded the work limit (private to the dynamics)."""


def max_time() -> float:
    """The longest time one flow may span (the kernel's limit on times, 1e8)."""
    return _checks._sweep_limits()[1]


def flow(scene: Scene, x0, times, rtol: float, atol: float, force=None):
    """The scene's flow from ``x0`` at t = 0 through ``times`` (one sign, in order away from 0), with the
    monodromy: (states (n, 2), monodromies (n, 2, 2), right-hand sides (n, 2)).  Ctrl-C stops it (the
    kernel polls the cancel flag); FlowError when it fails or needs more than MAX_FLOW_STEPS steps.
    ``force``: a user's force checked by ``_checks.force``, added to the scene's force law."""
    fx, words, wlen, nout, ngrid = scene._kernel_fields
    cancel = _interrupt.cancel_flag()
    times = np.ascontiguousarray(times, dtype=np.float64).reshape(-1)
    args = (fx, words, wlen, nout, ngrid, times, np.asarray(x0, dtype=np.float64), rtol, atol)
    extra = _checks.force_args(force)
    fn = _kernel.flow_monodromy_v
    # a short flow (most are: a period takes a few hundred steps) runs directly, since handing it to a
    # worker thread costs more than the flow; one that needs more steps starts again, interruptibly
    nmax = max(float(MAX_FLOW_STEPS), STEPS_PER_TIME * float(np.max(np.abs(times), initial=0.0)))
    ends, monos, fend, _nfev, status = fn(*args, float(_DIRECT_STEPS), *extra, cancel)
    if status == 2:
        ends, monos, fend, _nfev, status = _interrupt.call(fn, *args, nmax, *extra, cancel, cancel=cancel)
    if status == 3:                       # cancelled from another thread's flag
        raise KeyboardInterrupt
    if status:
        raise FlowError(_FLOW_STATUS.get(int(status), f"the flow failed (status {int(status)})"))
    return ends.T.copy(), monos.T.reshape(-1, 2, 2).copy(), fend.T.copy()


def forcing_frequency(scene: Scene) -> float:
    """The angular frequency of a scene's periodic forcing (the kernel's one definition: a drive, a vibrating
    pivot, or both at one frequency); ValueError naming the fields when there is none or two."""
    return contract.forcing_frequency(scene, "a periodic orbit")


def drive_period(scene: Scene, k: int) -> float:
    """k periods of a driven scene's forcing, refused (ValueError naming drive_frequency) beyond the time
    limit."""
    omega = forcing_frequency(scene)
    period = k * 2 * math.pi / omega
    if not period <= max_time():
        raise ValueError(f"drive_frequency: {k} drive period(s) of 2 pi / {omega!r} = "
                         f"{period:.3g} exceed the time limit {max_time():.0e} (work beyond the limits is refused)")
    return period


class NewtonError(ValueError):
    """Newton's iteration on a periodic orbit did not converge (private: the callers say where)."""

    def __init__(self, message: str, iterations: int, residual: float, state):
        super().__init__(message)
        self.iterations, self.residual, self.state = iterations, residual, state


class Evaluation:
    """One evaluation of an orbit problem at (u, p): the residual F, its Jacobian J in u, the monodromy M of
    the whole orbit, the time period T (and, for the half-period map, its derivative DG)."""

    __slots__ = ("F", "J", "M", "T", "DG")

    def __init__(self, F, J, M, T, DG=None):
        self.F, self.J, self.M, self.T, self.DG = F, J, M, T, DG


class OrbitProblem:
    """A periodic orbit as the root of F(u; p) = 0 in two unknowns u, for a scene family in one field.

    mode ``'map'``: u = (theta, v) at t = 0, F = P(u) - u - (2 pi winding, 0), P the flow over k drive
    periods (the stroboscopic map), J = M - I.
    mode ``'half'``: a symmetric orbit (theta, v, t) -> (2 pi m - theta, -v, t + T/2) of a scene with that
    symmetry (no torque, odd k): u a fixed point of G(u) = (2 pi m - theta(T/2), -v(T/2)); G o G = P, so
    M = DG^2, and the symmetry-breaking pitchfork of P is where DG has the eigenvalue -1.
    mode ``'section'``: an autonomous running orbit: u = (v, T) on the section theta = theta_s, F =
    (theta(T) - theta_s - 2 pi winding, v(T) - v).
    """

    def __init__(self, scene: Scene, mode: str, k: int = 1, winding: int = 0, param: str | None = None,
                 rtol: float = 1e-12, atol: float = 1e-12, m: int = 0, theta_s: float = 0.0, force=None):
        self.base, self.mode, self.k, self.winding, self.param = scene, mode, k, winding, param
        self.rtol, self.atol, self.m, self.theta_s, self.force = rtol, atol, m, theta_s, force
        self._cache: tuple | None = None

    def scene(self, p: float | None) -> Scene:
        if self.param is None or p is None:
            return self.base
        if self._cache is not None and self._cache[0] == p:
            return self._cache[1]
        try:
            sc = self.base.replace(**{self.param: float(p)})
        except SceneError as exc:     # a corrector's trial beyond the field's range: a failed evaluation
            raise FlowError(f"{self.param} = {float(p)!r} is outside the field's range ({exc})") from None
        self._cache = (p, sc)
        return sc

    def evaluate(self, u, p: float | None) -> Evaluation:
        sc = self.scene(p)
        u = np.asarray(u, dtype=np.float64)
        if self.mode == "section":
            T = float(u[1])
            if not 0.0 < T <= max_time():
                raise FlowError(f"the period {T:.3g} left (0, {max_time():.0e}]")
            end, mono, f = flow(sc, (self.theta_s, u[0]), [T], self.rtol, self.atol, self.force)
            end, mono, f = end[0], mono[0], f[0]
            F = np.array([end[0] - self.theta_s - 2 * math.pi * self.winding, end[1] - u[0]])
            J = np.array([[mono[0, 1], f[0]], [mono[1, 1] - 1.0, f[1]]])
            return Evaluation(F, J, mono, T)
        try:
            T = drive_period(sc, self.k)
        except ValueError as exc:        # a continuation in drive_frequency that reaches the time limit
            raise FlowError(str(exc)) from None
        if self.mode == "half":
            end, mono, _ = flow(sc, u, [0.5 * T], self.rtol, self.atol, self.force)
            end, DG = end[0], -mono[0]
            F = np.array([2 * math.pi * self.m - end[0] - u[0], -end[1] - u[1]])
            return Evaluation(F, DG - np.eye(2), DG @ DG, T, DG)
        end, mono, _ = flow(sc, u, [T], self.rtol, self.atol, self.force)
        F = end[0] - u - np.array([2 * math.pi * self.winding, 0.0])
        return Evaluation(F, mono[0] - np.eye(2), mono[0], T)

    def dFdp(self, u, p: float, F) -> np.ndarray:
        """dF/dp by a forward difference (it steers Newton and the tangent; the roots do not depend on it)."""
        dp = 1e-7 * max(1.0, abs(p))
        try:
            ev = self.evaluate(u, p + dp)
        except FlowError:             # at the upper edge of the field's range: the backward difference
            dp = -dp
            ev = self.evaluate(u, p + dp)
        return (ev.F - F) / dp


#: The trust region's first radius (a step of the state longer than this is shortened: a guess far from
#: an orbit), and its floor relative to the state (below it the iteration is stuck: no step lowers |F|).
_RADIUS0 = 1.0
_RADIUS_FLOOR = 1e-13
#: Steps of the trust region that must halve |F|^2 before it counts as stuck in a valley of |F|.
_STALL_STEPS = 5


def dogleg(A, F, radius: float, weights) -> tuple[np.ndarray, float]:
    """Powell's dogleg step for A d = -F inside ``|weights * d| <= radius`` (as MINPACK's hybrd; Nocedal
    & Wright, section 4.1): Newton's step when it fits, else the steepest descent of |F|^2 to its
    minimum along the gradient (the Cauchy point), then towards Newton's step up to the boundary.
    A singular or non-finite Newton step leaves the gradient's leg alone.  Returns the step and the
    decrease of |F + A d|^2 it predicts."""
    D = np.asarray(weights, dtype=np.float64)
    As = A / D                                 # the problem in the scaled unknowns y = D d
    try:
        yn = np.linalg.solve(As, -F)
        if not np.all(np.isfinite(yn)):
            yn = None
    except np.linalg.LinAlgError:
        yn = None
    if yn is not None and np.linalg.norm(yn) <= radius:
        y = yn
    else:
        g = As.T @ F                           # the gradient of |F|^2 / 2 in y
        gn = float(np.linalg.norm(g))
        Ag = float(np.linalg.norm(As @ g))
        if gn == 0.0 or Ag == 0.0:
            y = np.zeros_like(F) if yn is None else yn * (radius / np.linalg.norm(yn))
        else:
            yc = -(gn * gn / (Ag * Ag)) * g    # the Cauchy point
            cn = float(np.linalg.norm(yc))
            if cn >= radius or yn is None:
                y = yc * (min(radius, cn) / cn)
            else:                              # yc + s (yn - yc) on the boundary, 0 <= s <= 1
                dd = yn - yc
                a, b, c = float(dd @ dd), float(2 * yc @ dd), cn * cn - radius * radius
                s = (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)
                y = yc + s * dd
    d = y / D
    r = F + A @ d
    return d, float(F @ F - r @ r)


def _newton_step(A, F, cap: float = 1.0):
    """Newton's step for A d = -F, its state part shortened to ``cap`` (max norm); None when singular."""
    try:
        d = np.linalg.solve(A, -F)
    except np.linalg.LinAlgError:
        return None
    big = float(np.max(np.abs(d[:2])))
    if not math.isfinite(big):
        return None
    return d * (cap / big) if big > cap else d


def _stepped(u, p, d, plane):
    """The point (u, p) moved by the step d: d[2] moves the field p only on a pseudo-arclength plane."""
    return u + d[:2], (p if plane is None else p + float(d[2]))


def newton(problem: OrbitProblem, u, p, tol: float, maxit: int, plane=None):
    """Newton's iteration on F(u; p) = 0 in a trust region: the one corrector of the dynamics.

    plane None: p fixed, u the unknowns (a periodic orbit at one parameter).  plane = (n, U0): the
    parameter is a third unknown and the third equation is n . ((u, p) - U0) = 0 (the pseudo-arclength
    condition of a continuation step, or a branch switch).

    Each step is Powell's dogleg (:func:`dogleg`, as MINPACK's hybrd, with the exact Jacobian) in a
    trust region, first of radius 1 (the parameter scaled by its size), moved as hybrd moves it: a
    step is taken when |F|^2 falls by a fair share of what the linear model predicts, else the region
    shrinks and the step is tried again, so a rough guess slides down |F|^2 instead of jumping about
    the phase space; near the root the steps are Newton's.  The stroboscopic map of a long drive
    period makes |F|^2 a landscape of narrow valleys and minima that are not roots: where the region
    cannot lower it, or five steps have not halved it, one Newton step (its state part shortened to
    1) is taken whatever it gives, and the descent goes on from there.  Converged when the residual
    and the last step are below tol.  ``maxit`` bounds the evaluations of F (each is one flow).
    Returns (u, p, Evaluation at the root, evaluations); NewtonError (with how far it got) otherwise."""
    u = np.array(u, dtype=np.float64)
    p = None if p is None else float(p)
    weights = np.ones(2) if plane is None else np.array([1.0, 1.0, 1.0 / max(1.0, abs(p))])
    radius = _RADIUS0
    successes = 0
    last = prev = math.inf
    try:
        ev = problem.evaluate(u, p)
    except FlowError as exc:
        raise NewtonError(f"{exc} at the guess", 1, math.inf, (u, p)) from None
    res = float(np.max(np.abs(ev.F)))
    if not math.isfinite(res):
        raise NewtonError("the residual is not finite at the guess", 1, res, (u, p))
    evals = 1
    why = f"no convergence in {maxit} iterations"
    descent: list = []                 # |F|^2 along the current descent
    while True:
        scale = 1.0 + float(np.max(np.abs(u)))
        # converged: the residual below tol and the last step small, or the residual below tol twice
        # running (a nearly singular Jacobian, as at a multiplier next to 1, turns rounding-level
        # residuals into steps that never shrink: the state is as determined as it can be)
        if res <= tol * scale and (last <= math.sqrt(tol) * scale * 1e-2 or prev <= tol * scale) or res == 0.0:
            return u, p, ev, evals
        if evals > maxit:
            break
        if plane is None:
            A, F = ev.J, ev.F
        else:
            n, U0 = plane
            Fp = problem.dFdp(u, p, ev.F)
            A = np.zeros((3, 3))
            A[:2, :2], A[:2, 2], A[2] = ev.J, Fp, n
            F = np.append(ev.F, np.dot(n, np.append(u, p) - U0))
        if not np.all(np.isfinite(A)):
            raise NewtonError(f"the Jacobian is not finite at iteration {evals}", evals, res, (u, p))
        f2 = float(F @ F)
        descent.append(f2)
        stuck = len(descent) > _STALL_STEPS and f2 > 0.5 * descent[-1 - _STALL_STEPS]
        ok = False
        while not stuck:                       # shrink the region until a step lowers |F|
            d, predicted = dogleg(A, F, radius, weights)
            size = float(np.linalg.norm(d * weights))
            if predicted <= 0.0 or size == 0.0:
                break
            ut, pt = _stepped(u, p, d, plane)
            evals += 1
            try:
                evt = problem.evaluate(ut, pt)
                Ft = evt.F if plane is None else np.append(evt.F, np.dot(n, np.append(ut, pt) - U0))
                f2t = float(Ft @ Ft)
            except FlowError:
                evt, f2t = None, math.inf
            rest = float(np.max(np.abs(evt.F))) if evt is not None else math.inf
            rho = (f2 - f2t) / predicted if math.isfinite(f2t) else -math.inf
            # a step within tolerance is taken whatever the model said (at the root |F| is rounding)
            ok = rho >= 1e-4 or (math.isfinite(rest) and rest <= tol * (1.0 + float(np.max(np.abs(ut)))))
            # the radius as hybrd moves it (More, Garbow & Hillstrom, MINPACK-1, hybrd)
            if rho < 0.1:
                radius, successes = 0.5 * radius, 0
            else:
                successes += 1
                if rho >= 0.5 or successes > 1:
                    radius = max(radius, 2.0 * size)
                if abs(rho - 1.0) <= 0.1:
                    radius = 2.0 * size
            if ok or radius <= _RADIUS_FLOOR * scale or evals > maxit:
                break
        if not ok and evals <= maxit:
            # stuck in a valley or at a minimum of |F| that is not a root: one shortened Newton step
            d = _newton_step(A, F)
            if d is None:
                why = f"the Jacobian is singular at iteration {evals}"
                break
            ut, pt = _stepped(u, p, d, plane)
            evals += 1
            try:
                evt = problem.evaluate(ut, pt)
            except FlowError as exc:
                why = f"{exc} at iteration {evals}"
                break
            rest = float(np.max(np.abs(evt.F)))
            if not math.isfinite(rest):
                why = f"the residual is not finite at iteration {evals}"
                break
            descent, radius, ok = [], _RADIUS0, True
        if not ok:
            break
        prev = res
        last = float(np.max(np.abs(d)))
        u, p, ev, res = ut, pt, evt, rest
    raise NewtonError(why, evals, res, (u, p))


#: The error of a function of the monodromy, in units of rtol (1 + |X|)^2 (X the matrix it is made of): the
#: flow's error moves tr X and det X by about rtol |X| and rtol |X|^2; measured on 40 random orbits (flows
#: at rtol 1e-12 against 1e-15) below 0.22 of it, so 100 leaves a margin of 450.
MONODROMY_ERROR = 100.0


def monodromy_error(X, rtol: float) -> float:
    """The bound on the error of tr X and det X (X a monodromy or its half) for a flow at rtol."""
    return MONODROMY_ERROR * rtol * (1.0 + float(np.linalg.norm(X))) ** 2


def stability_certificate(M, rtol: float, autonomous: bool = False) -> tuple[bool, bool, float]:
    """(stable, certified, error): the verdict from the Jury conditions of a real 2 x 2 monodromy (every
    multiplier inside the unit circle iff 1 - tr + det, 1 + tr + det and 1 - det are all positive), and
    whether it is decided beyond the conditions' error (stable: all three above it; unstable: one below
    minus it).  An autonomous orbit's trivial multiplier 1 is left out: its verdict is 1 - |det M|."""
    tr, det = float(np.trace(M)), float(np.linalg.det(M))
    err = monodromy_error(M, rtol)
    jury = (1.0 - abs(det),) if autonomous else (1.0 - tr + det, 1.0 + tr + det, 1.0 - det)
    stable = min(jury) > 0.0
    return stable, (min(jury) > err if stable else min(jury) < -err), err


def liouville_residual(scene: Scene, M, T: float, force=None) -> float:
    """|det M - exp(-damping T)|: the certificate of a monodromy over the time T (Liouville's formula:
    the pendulum's flow shrinks areas at the constant rate ``damping``); NaN where the rate is not
    constant (quadratic drag, a user's force)."""
    if scene.drag != 0.0 or force is not None:
        return math.nan
    return float(abs(np.linalg.det(M) - math.exp(-scene.damping * T)))


def multipliers_of(M) -> np.ndarray:
    """The eigenvalues of a monodromy, complex, largest modulus first."""
    mu = np.linalg.eigvals(M).astype(complex)
    return mu[np.argsort(-np.abs(mu), kind="stable")]


def reduce_angle(theta: float) -> float:
    """theta taken to [-pi, pi] (the force is 2 pi periodic)."""
    return float(theta) - 2 * math.pi * round(float(theta) / (2 * math.pi))


def check_guess(guess, scene: Scene) -> np.ndarray:
    """A state (theta, v): two reals, |theta| <= 2^52, theta reduced to [-pi, pi]."""
    if guess is None:
        guess = (scene.theta0, scene.v0)
    if isinstance(guess, (str, bytes)) or not hasattr(guess, "__len__") or len(guess) != 2:
        raise TypeError(f"guess must be a state (theta, v) of two numbers, got {guess!r:.60}")
    th = _checks.angle(guess[0], "guess[0] (theta)")
    v = _checks.real(guess[1], "guess[1] (v)")
    return np.array([reduce_angle(th), v])


def periodic_orbit(scene: Scene, guess: tuple[float, float] | None = None, k: int = 1, winding: int = 0,
                   tol: float = 1e-11, rtol: float = 1e-12, atol: float = 1e-12, maxit: int = 100,
                   force: object = None, force_params: ArrayLike | None = None) -> PeriodicOrbit:
    """A period-k orbit of a driven scene's stroboscopic map, by Newton on the monodromy.

    The map ``P`` takes the state at ``t = 0`` to the state ``k`` drive periods
    later; a periodic orbit is a root of ``P(x) - x - (2 pi winding, 0)``.  The
    flow and its monodromy matrix (the variational equations) come from GSL's
    rk8pd, the root from Newton's method with that exact Jacobian ``M - I``
    in a trust region (Powell's dogleg, as MINPACK's hybrd), so that a rough
    guess slides down the residual rather than jumping about the phase space.
    The Floquet multipliers are the eigenvalues of the monodromy; their
    product is ``exp(-damping * period)`` (Liouville), and ``log|mu| / period``
    are the orbit's Lyapunov exponents, the ones a ``lyapunov`` sweep measures
    on an attracting orbit.  Ctrl-C stops the call; one flow takes at most
    ``MAX_FLOW_STEPS`` steps.

    Parameters
    ----------
    scene : Scene
        A driven rigid pendulum in the uniform field (``drive_amplitude`` and
        ``drive_frequency`` non-zero); ``eps``, ``damping``, ``torque`` and
        ``drive_phase`` are used.
    guess : (float, float), optional
        The starting state ``(theta, v)``, ``|theta| <= 2**52``; default
        ``(scene.theta0, scene.v0)``.
    k : int, optional
        The period in drive periods (default 1).
    winding : int, optional
        Turns per period of a running orbit (default 0, an oscillation).
    tol : float, optional
        Newton's stopping tolerance on the residual (default 1e-11).
    rtol, atol : float, optional
        The integrator's tolerances (default 1e-12; ``0 < rtol < 1``, ``0 <= atol < 1``).
    maxit : int, optional
        The most Newton iterations (default 100).
    force, force_params : optional
        A user's force added to the force law, as in :func:`pendula.simulate`
        (its derivatives for the monodromy by central differences).

    A vibrating pivot (``pivot_amplitude``, ``pivot_frequency``) drives the
    scene too: its period is the pivot's when there is no drive, and a drive
    with a pivot must share its frequency.  Drag is accepted (its force is
    once differentiable at v = 0); friction is not (the flow sticks).

    Returns
    -------
    PeriodicOrbit
        The state on the section, the period, the multipliers and exponents.

    Raises
    ------
    TypeError
        If an argument is not of its kind (a string, bytes or bool where a number is wanted).
    ValueError
        If the scene is not driven, an argument is out of range, ``k`` drive
        periods exceed the time limit 1e8, the flow exceeds the work limit, or
        Newton's iteration fails (the message says where it got).
    NotImplementedError
        For the flexible cord, the cycloidal guide and the non-uniform fields.

    See Also
    --------
    equilibria : the rest points of an autonomous scene.
    continue_orbit : the orbit followed as a parameter moves, and its bifurcations.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=0.9, drive_frequency=2/3)
    >>> po = pendula.periodic_orbit(sc, guess=(0.5, 0.5))
    >>> print(f"{po.theta:.6f} {po.v:.6f} {po.stable}")
    -0.560228 1.933586 True
    >>> print(f"{po.exponents[0]:.6f}")
    -0.250000
    """
    # the capability table: a smooth deterministic flow with a periodic forcing (noise, dry friction refused)
    contract.require(scene, "periodic_orbit", force=force is not None)
    forcing_frequency(scene)
    k = _checks.count(k, "k", 1, 10**4)
    maxit = _checks.count(maxit, "maxit", 1, 10**4)
    winding = _checks.count(winding, "winding", -10**9, 10**9)
    tol = _checks.real(tol, "tol", 0.0, lo_open=True)
    rtol, atol = _checks.tolerances(rtol, atol)
    x0 = check_guess(guess, scene)
    period = drive_period(scene, k)
    uf = None if force is None and force_params is None else _checks.force(force, force_params)
    problem = OrbitProblem(scene, "map", k, winding, rtol=rtol, atol=atol, force=uf)
    try:
        x, _, ev, _ = newton(problem, x0, None, tol, maxit)
    except NewtonError as exc:
        if uf is not None:
            uf.reraise()
        u = exc.state[0]
        raise ValueError(f"periodic_orbit: Newton's iteration from guess {tuple(x0.tolist())} failed: {exc}; "
                         f"it got to theta={u[0]:.6g}, v={u[1]:.6g} with residual {exc.residual:.3g} "
                         "(try another guess, or a looser tol)") from None
    if uf is not None:
        uf.reraise()
    m = ev.M.copy()
    mu = multipliers_of(m)
    det_res = liouville_residual(scene, m, period, uf)
    _, decided, err = stability_certificate(m, rtol)
    return PeriodicOrbit(reduce_angle(x[0]), float(x[1]), period, mu, np.log(np.abs(mu)) / period, m,
                         int(winding), float(np.max(np.abs(ev.F))), det_res, err,
                         bool(decided and not det_res > err))
