"""Continuation: a periodic orbit or an equilibrium followed as one scene field moves, with its bifurcations.

Pseudo-arclength continuation (Keller; Kuznetsov, *Elements of Applied
Bifurcation Theory*, section 10.2) on the one Newton-and-monodromy core of
:mod:`.periodic`: the orbit's two unknowns and the parameter are three
unknowns, the third equation fixes the arclength along the tangent, so the
branch is followed through turning points.  Bifurcations are found by the
sign of test functions of the monodromy ``M`` (``det(M - I)``, ``det(M + I)``,
``det M - 1`` for a complex pair, the tangent's parameter component at a
fold), counted only where the sign is decided beyond the test function's
error, and located by solving the test function's root along the branch
(Illinois regula falsi, each evaluation a corrected point of the branch), not
by the step size.  The pendulum's symmetry (theta, v, t) -> (-theta, -v,
t + T/2) of an untorqued drive is used exactly: a symmetric orbit is followed
as a fixed point of the half-period map G (G o G = P), where the
symmetry-breaking pitchfork is a regular flip of G.  The homoclinic end of a
running autonomous orbit is located by the splitting of the saddle's unstable
manifold from the next saddle's stable one.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .. import _checks
from ..scene import Scene, SceneError, _NUMBERS, _WHOLE
from .equilibria import equilibria
from ..systems.contract import require, time_scales
from .branches import BIFURCATION_KINDS, Bifurcation, Branch, ContinuationError  # noqa: F401 (re-exported)
from .branch_functions import _decided, _root, _stable, _tangent, _test_errors, _tests
from .homoclinic import _first_return, _splitting
from .periodic import (FlowError, NewtonError, OrbitProblem, check_guess, drive_period, flow,
                       liouville_residual, multipliers_of, newton, reduce_angle, stability_certificate)

__all__ = ["Bifurcation", "Branch", "ContinuationError", "continue_orbit", "BIFURCATION_KINDS"]

#: The most points of one continuation (the work limit).
MAX_POINTS = 20_000
#: A branch ends where a multiplier's modulus exceeds this: single shooting cannot follow it further.
MAX_MULTIPLIER = 1e6
_TOL = 1e-11          # Newton's tolerance on the residual (the flow's own accuracy is about 1e-12)
_MAXIT = 10           # corrector iterations before the step is halved


def _param_value(scene: Scene, param) -> float:
    if not isinstance(param, str):
        raise TypeError(f"param must be the name of a scene field (str), not {type(param).__name__}")
    names = {f.name for f in dataclasses.fields(Scene)}
    if param not in names:
        raise ValueError(f"param: {param!r} is not a scene field")
    if param not in _NUMBERS or param in _WHOLE:
        raise ValueError(f"param: the scene field {param!r} is not a real number; continuation needs one")
    return float(getattr(scene, param))


def _stop_value(scene: Scene, param: str, p0: float, stop) -> float:
    stop = _checks.real(stop, "stop")
    if stop == p0:
        raise ValueError(f"stop: equals the scene's {param} = {p0!r}; give the value to continue to")
    if param in ("drive_amplitude", "drive_frequency") and scene.drive_amplitude != 0 and (stop <= 0) != (p0 <= 0):
        raise ValueError(f"stop: {param} = {stop!r} is on the other side of 0 from the scene's {p0!r}; "
                         "at 0 the scene is no longer driven")
    try:
        scene.replace(**{param: stop})
    except SceneError as exc:
        raise SceneError(f"stop: {exc}") from None
    return stop


def _cycle(prob, U) -> np.ndarray:
    """The orbit's k section points (theta, v), one drive period apart (one point on an autonomous
    orbit's section), theta in [-pi, pi]."""
    if prob.mode == "section":
        return np.array([[reduce_angle(prob.theta_s), float(U[0])]])
    pts = np.empty((prob.k, 2))
    pts[0] = U[:2]
    if prob.k > 1:
        sc = prob.scene(float(U[2]))
        td = drive_period(sc, 1)
        end, _, _ = flow(sc, U[:2], [j * td for j in range(1, prob.k)], prob.rtol, prob.atol, prob.force)
        pts[1:] = end
    pts[:, 0] = [reduce_angle(x) for x in pts[:, 0]]
    return pts


def _residuals(prob, U, ev) -> tuple[float, float]:
    """The certificates of a point's multipliers: |det M - exp(-damping T)| (Liouville; NaN with drag
    or a user's force, whose divergence is not constant) and, on an autonomous orbit, the distance
    of the trivial multiplier from 1 (NaN on a driven one)."""
    sc = prob.scene(float(U[2]))
    T = float(ev.T) if prob.mode == "section" else drive_period(sc, prob.k)
    det = liouville_residual(sc, ev.M, T, prob.force)
    trivial = float(np.min(np.abs(multipliers_of(ev.M) - 1.0))) if prob.mode == "section" else math.nan
    return det, trivial


def _certified(prob, U, ev) -> bool:
    """The point's stability verdict decided beyond the monodromy's error, its Liouville residual within it."""
    _, decided, err = stability_certificate(ev.M, prob.rtol, prob.mode == "section")
    det, _ = _residuals(prob, U, ev)
    return bool(decided and not det > err)


# ---------------------------------------------------------------- the branch tracer

def resolution(p0: float, stop: float) -> float:
    """The smallest step a continuation takes from p0 towards stop: 1e-10 of the parameter's size (at
    least 1e-10): the corrector resolves a point to about 1e-11, so a shorter step moves by noise."""
    return 1e-10 * max(1.0, abs(p0), abs(stop))


def _check_steps(param: str, p0: float, stop: float, step: float | None) -> None:
    """Work the steps cannot do is refused before it starts: a stop or a first step within the
    parameter's resolution (nothing would move), or a step too short to reach the stop in MAX_POINTS."""
    res = resolution(p0, stop)
    if abs(stop - p0) < res:
        raise ValueError(f"stop: {stop!r} lies within the resolution {res:.1e} of the scene's {param} = {p0!r}; "
                         "a continuation cannot move by less")
    if step is not None:
        if step < res:
            raise ValueError(f"step: {step!r} is below the resolution {res:.1e} of {param} near {p0!r} "
                             "(the corrector resolves a point to about 1e-11: a shorter step does not move)")
        if abs(stop - p0) / (4 * step) > MAX_POINTS:
            raise ValueError(f"step: {step!r} is too short to reach stop = {stop!r} from {param} = {p0!r} "
                             f"within the work limit of {MAX_POINTS} points (steps grow to 4 x step)")


class _Tracer:
    """The state of one continue_orbit call."""

    def __init__(self, scene, param, p0, stop, follow, step):
        self.scene, self.param, self.p0, self.stop, self.follow = scene, param, p0, stop, follow
        self.snic_probed = False      # the saddle-node end is searched once per branch
        span = abs(stop - p0)
        self.h0 = step if step is not None else min(0.05, span / 20)
        self.hmax = max(self.h0, span / 10) if step is None else step * 4
        self.hmin = resolution(p0, stop)
        self.h0 = max(self.h0, self.hmin)
        self.rows: list = []          # (p, theta, v, period, mu0, mu1, stable, segment)
        self.bifs: list = []
        self.spawns: list = []        # (index in bifs, kind, problem, U, Evaluation, tangent): the branch points
        self.segment = 0
        self.end = ""

    # -- records
    def _period(self, prob, ev) -> float:
        return float(ev.T) if prob.mode == "section" else float(prob.k)

    def _state(self, prob, u):
        if prob.mode == "section":
            return reduce_angle(prob.theta_s), float(u[0])
        return reduce_angle(u[0]), float(u[1])

    def record(self, prob, U, ev):
        th, v = self._state(prob, U[:2])
        mu = multipliers_of(ev.M)
        self.rows.append((float(U[2]), th, v, self._period(prob, ev), mu[0], mu[1], _stable(prob.mode, ev),
                          self.segment, _cycle(prob, U)) + _residuals(prob, U, ev) + (_certified(prob, U, ev),))

    def bifurcation(self, kind, prob, U, ev):
        th, v = self._state(prob, U[:2])
        self.bifs.append(Bifurcation(kind, float(U[2]), self._period(prob, ev), th, v, multipliers_of(ev.M),
                                     *self._where(prob, U[2]), *_residuals(prob, U, ev), cycle=_cycle(prob, U)))

    def _where(self, prob, p) -> tuple:
        """(scene at p, param, winding) of a bifurcation record: where continue_bifurcation starts."""
        try:
            sc = self.scene.replace(**{self.param: float(p)})
        except SceneError:
            sc = None
        return sc, self.param, int(prob.winding)

    def branch(self) -> Branch:
        r = self.rows
        col = (lambda i, dt=float: np.array([x[i] for x in r], dtype=dt))
        mus = np.array([[x[4], x[5]] for x in r], dtype=complex).reshape(-1, 2)
        K = max((len(x[8]) for x in r), default=1)
        cyc = np.full((len(r), K, 2), np.nan)
        for i, x in enumerate(r):
            cyc[i, :len(x[8])] = x[8]
        return Branch(self.scene, self.param, col(0), col(1), col(2), col(3), mus, col(6, bool), col(7, int),
                      tuple(self.bifs), self.end, cycle=cyc, det_residual=col(9), trivial_residual=col(10),
                      certified=col(11, bool))

    def fail(self, message):
        self.end = "error"
        raise ContinuationError(f"{self.param}: {message}", self.branch())

    # -- the corrector at a given arclength along a tangent
    def correct(self, prob, Upred, n, U0, maxit=_MAXIT):
        u, p, ev, it = newton(prob, Upred[:2], Upred[2], _TOL, maxit, plane=(n, U0))
        return np.append(u, p), ev, it

    def tangent(self, prob, U, ev, previous=None):
        Fp = prob.dFdp(U[:2], U[2], ev.F)
        return _tangent(ev.J, Fp, previous), Fp

    # -- one branch (a segment), from a corrected point with its tangent
    def run_segment(self, prob, U, ev, t):
        h = self.h0
        lo, hi = sorted((self.p0, self.stop))
        tests = _tests(prob.mode, ev)
        self.signs = _decided(prob.mode, ev, tests, prob.rtol)
        stable = _stable(prob.mode, ev)
        T_first = float(ev.T)
        while True:
            if len(self.rows) >= MAX_POINTS:
                self.end = f"work limit: {MAX_POINTS} points"
                return None
            Upred = U + h * t
            clipped = None
            if not lo <= Upred[2] <= hi and t[2] != 0.0:
                # never predict past the stop (or the start, after a turn): a field's edge may lie there
                clipped = hi if Upred[2] > hi else lo
                Upred = U + ((clipped - U[2]) / t[2]) * t
                Upred[2] = clipped
            try:
                Ub, evb, it = self.correct(prob, Upred, t, Upred)
                tb, _ = self.tangent(prob, Ub, evb, t)
            except (NewtonError, FlowError) as exc:
                if prob.mode == "section" and self.homoclinic(prob, U, ev, t, h):
                    return None
                h *= 0.5
                if h < self.hmin:
                    self.fail(f"the branch cannot be continued past {self.param} = {float(U[2])!r} "
                              f"(theta={self._state(prob, U[:2])[0]:.6g}, v={self._state(prob, U[:2])[1]:.6g}): "
                              f"{exc}; the step shrank below {self.hmin:.1e}")
                continue
            testsb = _tests(prob.mode, evb)
            # a test function that moves far in one step could hide two sign changes: shorter steps
            # (far relative to its size: an unstable orbit's 1 + tr M + det M may be in the thousands)
            jump = any(abs(testsb[key] - tests[key]) > 0.5 * (1 + min(abs(testsb[key]), abs(tests[key])))
                       for key in ("period-doubling", "pitchfork", "plus")
                       if key in tests and math.isfinite(tests[key]) and math.isfinite(testsb[key]))
            if (np.dot(t, tb) < 0.98 or jump) and h > 1e3 * self.hmin:
                h *= 0.5
                continue
            # the stop, or the start side after a turn: the last point exactly there
            pb = Ub[2]
            final = None
            if pb > hi or pb < lo or clipped is not None:
                edge = clipped if clipped is not None else hi if pb > hi else lo
                n = np.array([0.0, 0.0, 1.0])
                frac = (edge - U[2]) / (pb - U[2]) if pb != U[2] else 1.0
                Ustart = U + frac * (Ub - U)
                Ustart[2] = edge                  # exactly (rounding could put it past a field's edge)
                try:
                    Ue, eve, _ = self.correct(prob, Ustart, n, np.array([0.0, 0.0, edge]), maxit=20)
                except (NewtonError, FlowError) as exc:
                    self.fail(f"the branch could not be corrected at {self.param} = {float(edge)!r}: {exc}")
                Ub, evb = Ue, eve
                tb, _ = self.tangent(prob, Ub, evb, t)
                testsb = _tests(prob.mode, evb)
                final = "stop" if edge == self.stop else f"turned back to {self.param} = {float(edge)!r} (past a fold)"
            # bifurcations between U and Ub
            events = self.events(prob, U, ev, t, tests, Ub, evb, tb, testsb)
            stableb = _stable(prob.mode, evb)
            for s, kind, Uc, evc in events:
                if Uc is None:                # located on the symmetric orbit (the half-period map)
                    Uh, evh = evc
                    th, v = reduce_angle(Uh[0]), float(Uh[1])
                    self.bifs.append(Bifurcation(kind, float(Uh[2]), float(prob.k), th, v, multipliers_of(evh.M),
                                                 *self._where(prob, Uh[2]), *_residuals(prob, Uh, evh),
                                                 cycle=_cycle(prob, Uh)))
                    continue
                self.bifurcation(kind, prob, Uc, evc)
                if kind in ("pitchfork", "period-doubling"):
                    self.spawns.append((len(self.bifs) - 1, kind, prob, Uc, evc, t))
                if self.follow == "stable" and stable:
                    if kind in ("pitchfork", "period-doubling"):
                        # the stable side of the point: follow the child if this branch lost stability
                        if not stableb:
                            self.record(prob, Uc, evc)
                            return ("switch", kind, prob, Uc, evc, t)
                    elif kind in ("fold", "neimark-sacker") and not stableb:
                        self.record(prob, Uc, evc)
                        self.end = (f"{kind} at {self.param} = {float(Uc[2])!r}: the attracting orbit ends there "
                                    "(the motion jumps to another attractor)")
                        return None
            self.record(prob, Ub, evb)
            if final is not None:
                self.end = final
                return None
            big = float(np.max(np.abs(multipliers_of(evb.M))))
            if big > MAX_MULTIPLIER:
                self.end = (f"at {self.param} = {float(Ub[2])!r} a multiplier reaches {big:.1e}: too unstable for single "
                            "shooting (Newton's basin shrinks to the flow's error times that)")
                return None
            if prob.mode == "section" and evb.T > 1.5 * T_first and evb.T > ev.T \
                    and self.homoclinic(prob, Ub, evb, tb, abs(Ub[2] - U[2])):
                # the period grows: the homoclinic orbit lies within a few steps
                return None
            if it <= 3:
                # (an autonomous period grows without bound near the homoclinic: steps grow with it)
                h = min(1.5 * h, max(self.hmax, 0.2 * float(evb.T)) if prob.mode == "section" else self.hmax)
            U, ev, t, tests, stable = Ub, evb, tb, testsb, stableb

    def events(self, prob, Ua, eva, ta, tests_a, Ub, evb, tb, tests_b):
        """The bifurcations between two points, located, in the order met.

        A test function counts as changed only where its sign is decided on both sides (beyond its
        error, :func:`_decided`; the last decided sign is carried over points where it is not), and a
        bifurcation is reported only at a solved root of its test function: the located point's value
        within its error, or a bracket of opposite decided signs shrunk to the resolution."""
        sb = float(np.dot(ta, Ub - Ua))
        found = []
        folded = (ta[2] > 0) != (tb[2] > 0)
        signs_b = _decided(prob.mode, evb, tests_b, prob.rtol)
        changed = {key for key, sgn in signs_b.items()
                   if sgn and self.signs.get(key) and sgn != self.signs[key]}
        for key, sgn in signs_b.items():
            if sgn:
                self.signs[key] = sgn
        cand = []
        if folded and "fold" in changed:
            cand.append(("fold", "fold"))
        elif folded and prob.mode == "map":
            # the branch turns with no multiplier through +1: a branch point met from its child (the
            # asymmetric orbit comes down to the pitchfork of the symmetric one and goes back up)
            pf = self.pitchfork_from_child(prob, Ua, Ub, ta)
            if pf is not None:
                found.append((0.5 * sb, "pitchfork", None, pf))
        for key in ("pitchfork", "period-doubling", "neimark-sacker"):
            if key in changed:
                cand.append((key, key))
        if "fold" in changed and not folded and prob.mode == "map":
            cand.append(("pitchfork", "fold"))
        for kind, key in cand:
            if not (tests_a[key] > 0) != (tests_b[key] > 0):
                # the sign changed across points where it was below its error: the root lies there, at
                # the resolution of the computation (the last such point)
                found.append((0.0, kind, Ua, eva))
                continue

            def g(s, key=key):
                Upred = Ua + (s / sb) * (Ub - Ua) if sb else Ua
                Uc, evc, _ = self.correct(prob, Upred, ta, Ua + s * ta, maxit=20)
                return _tests(prob.mode, evc)[key], (Uc, evc)
            try:
                s, (Uc, evc), gx, width = _root(g, 0.0, tests_a[key], sb, tests_b[key], xtol=1e-13 * (1 + abs(sb)))
            except (NewtonError, FlowError) as exc:
                self.fail(f"the {kind} between {self.param} = {float(Ua[2])!r} and {float(Ub[2])!r} could not be located: {exc}")
            if not (abs(gx) <= _test_errors(prob.mode, evc, prob.rtol)[key] or width <= 1e-13 * (1 + abs(sb))):
                self.fail(f"the {kind} between {self.param} = {float(Ua[2])!r} and {float(Ub[2])!r} could not be "
                          f"solved: its test function is {gx:.3g} at the last point")
            found.append((s, kind, Uc, evc))
        found.sort(key=lambda e: e[0])
        return found

    def pitchfork_from_child(self, prob, Ua, Ub, ta):
        """The symmetry-breaking pitchfork met from its asymmetric child, located on the symmetric orbit
        (the half-period map's test function 1 + tr DG + det DG, solved in the parameter); None when
        the scene has no such symmetry or no symmetric orbit lies next to the turn.  Returns
        (U, Evaluation) of the symmetric orbit at the pitchfork."""
        sc = prob.base
        if prob.winding != 0 or prob.k % 2 == 0 or sc.torque != 0.0 or self.param == "torque" \
                or sc.pivot_amplitude != 0.0:
            return None
        try:
            T = drive_period(prob.scene(float(Ua[2])), prob.k)
            end, _, _ = flow(prob.scene(float(Ua[2])), Ua[:2], [0.5 * T], prob.rtol, prob.atol)
        except (ValueError, FlowError):
            return None
        m = round((end[0, 0] + Ua[0]) / (2 * math.pi))
        half = OrbitProblem(sc, "half", prob.k, 0, self.param, prob.rtol, prob.atol, m=m)
        state = {"u": np.array(Ua[:2], dtype=float)}

        def g(p):
            u, _, ev, _ = newton(half, state["u"], p, _TOL, 30)
            state["u"] = u
            val = _tests("half", ev)["pitchfork"]
            err = _test_errors("half", ev, prob.rtol)["pitchfork"]
            return (val if abs(val) > err else 0.0), (np.append(u, p), ev)
        # the turn, and the pitchfork with it, lies beyond the two points in the direction the branch went
        up = ta[2] > 0
        pa, pb = float(Ua[2]), float(Ub[2])
        near = max(pa, pb) if up else min(pa, pb)
        lo_edge, hi_edge = sorted((self.p0, self.stop))
        try:
            ga, _ = g(near)
            if ga == 0.0:
                return None
            delta = abs(pa - pb) + self.hmin
            for _ in range(40):
                far = near + delta if up else near - delta
                if not lo_edge <= far <= hi_edge:
                    return None
                gb, _ = g(far)
                if gb != 0.0 and (gb > 0) != (ga > 0):
                    break
                delta *= 2.0
            else:
                return None
            p, payload, gx, width = _root(g, near, ga, far, gb, xtol=1e-13 * max(1.0, abs(near)))
        except (NewtonError, FlowError):
            return None
        if not (gx == 0.0 or width <= 1e-13 * max(1.0, abs(near))):
            return None
        return payload

    # -- branch switching at a pitchfork or a period doubling
    def child_start(self, kind, prob, Us, evs, t_parent, sign: int = 1):
        """The first point of the child branch at a pitchfork or a period doubling, on the side ``sign``
        of the critical eigenvector (at a pitchfork the two sides are the two children; at a period
        doubling both give the one child of period 2k): (problem, U, Evaluation, tangent pointing away
        from the branch point), or a string saying why there is none."""
        k2, w2 = (prob.k, prob.winding) if kind == "pitchfork" else (2 * prob.k, 2 * prob.winding)
        if k2 > 10**4:
            return f"{kind} at {self.param} = {float(Us[2])!r}: the child's period exceeds 10000 drive periods"
        child = OrbitProblem(prob.base, "map", k2, w2, self.param, prob.rtol, prob.atol)
        parent_map = OrbitProblem(prob.base, "map", prob.k, prob.winding, self.param, prob.rtol, prob.atol)
        target = 1.0 if kind == "pitchfork" else -1.0
        mu, vec = np.linalg.eig(evs.M)
        i = int(np.argmin(np.abs(mu - target)))
        e = np.real(vec[:, i])
        e = e / np.linalg.norm(e)
        if e[0] < 0 or (e[0] == 0 and e[1] < 0):
            e = -e
        E = sign * np.append(e, 0.0)
        n = E - np.dot(E, t_parent) * t_parent
        n = n / np.linalg.norm(n)
        # the child next to the branch point (close: the next doubling of a cascade may be near)
        for hb in (1e-5, 1e-4, 1e-3, 1e-2):
            Upred = Us + (hb / np.dot(n, E)) * E
            try:
                U1, ev1, _ = self.correct(child, Upred, n, Upred, maxit=20)
                off = float(np.max(np.abs((prob if kind == "pitchfork" else parent_map).evaluate(U1[:2], U1[2]).F)))
            except (NewtonError, FlowError):
                continue
            # a child distinct from the parent, its parameter offset (c hb^2) resolved above the noise
            if off > 0.1 * hb and abs(U1[2] - Us[2]) > 1e-9 * max(1.0, abs(Us[2])):
                break
        else:
            return f"{kind} at {self.param} = {float(Us[2])!r}: no child branch found next to it"
        t1, _ = self.tangent(child, U1, ev1)
        if np.dot(t1, U1 - Us) < 0:
            t1 = -t1
        return child, U1, ev1, t1

    # -- branch switching at a pitchfork or a period doubling
    def switch(self, kind, prob, Us, evs, t_parent):
        first = self.child_start(kind, prob, Us, evs, t_parent)
        if isinstance(first, str):
            self.end = first
            return None
        child, U1, ev1, t1 = first
        # supercritical (the child on the far side, attracting: its multiplier 1 - O(hb^2) inside the
        # circle) or subcritical (on the near side, repelling)
        if (U1[2] - Us[2]) * (self.stop - Us[2]) < 0:
            self.end = (f"{kind} at {self.param} = {float(Us[2])!r} is subcritical: no attracting child branch "
                        "(the motion jumps to another attractor)")
            return None
        self.segment += 1
        self.record(child, U1, ev1)
        return child, U1, ev1, t1

    # -- the homoclinic end of an autonomous running orbit
    def homoclinic(self, prob, U, ev, t, dp) -> bool:
        """Locate the parameter where the saddle's unstable manifold reaches the next saddle, beyond U
        in the branch's direction; True (and the branch ended) when it lies within 4 dp."""
        sign = 1.0 if t[2] > 0 else -1.0
        p = float(U[2])
        d0 = _splitting(prob.scene(p), prob.winding, prob.rtol, prob.atol)
        if d0 == math.inf and self.saddle_node_end(prob, U, ev, sign):
            return True
        if not (d0 is not None and d0 > 0):
            return False
        q = p + sign * max(4 * dp, 1e-12 * max(1.0, abs(p)))
        if (q - self.stop) * (self.stop - p) > 0 or not math.isfinite(q):
            return False
        try:
            dq = _splitting(prob.scene(q), prob.winding, prob.rtol, prob.atol)
        except SceneError:
            return False
        if dq is not None and dq > 0:
            return False            # the manifold still falls short of the next saddle 4 dp on

        def g(x):
            d = _splitting(prob.scene(x), prob.winding, prob.rtol, prob.atol)
            return (-1.0 if d is None else d), None
        ph, _, _, _ = _root(g, p, d0, q, -1.0 if dq is None else dq, xtol=1e-14 * max(1.0, abs(p)))
        sc = prob.scene(ph)
        sad = [e for e in equilibria(sc) if e.kind == "saddle"]
        theta = sad[0].theta if sad else math.nan
        self.bifs.append(Bifurcation("homoclinic", float(ph), math.inf, theta, 0.0, np.array([1.0, 0.0], dtype=complex),
                                     *self._where(prob, ph)))
        self.end = f"homoclinic at {self.param} = {float(ph)!r}: the period diverges"
        return True


    def saddle_node_end(self, prob, U, ev, sign) -> bool:
        """The end of a running orbit on the rest points born on it (a saddle-node on an invariant circle,
        SNIC: the period diverges like 1 / sqrt(distance)), met where the period grows and no rest point
        exists yet; True (and the branch ended) when found.  Probed once per branch: the birth of the rest
        points is searched ahead by doubling steps (an equilibria call costs about 0.2 ms) and bisected to
        rounding; just past it the saddle's unstable manifold must fall back (no running orbit), else the
        homoclinic torque lies past the birth and is solved there when it is within 1e-6 of it (beyond, the
        branch goes on to it as usual).  The branch then approaches the end in steps dividing the distance
        by 4 (each a corrected orbit at fixed parameter), not creeping in steps that shrink with the
        distance."""
        if self.snic_probed:
            return False
        self.snic_probed = True
        p = float(U[2])
        scale = max(1.0, abs(p))

        def born(x):
            try:
                return len(equilibria(prob.scene(x))) > 0
            except SceneError:
                return None
        lo, hi, step = p, None, 1e-3 * max(abs(p - self.p0), 1e-10 * scale)
        while (hi is None) and (lo - self.stop) * sign < 0:
            q = lo + sign * step
            if (q - self.stop) * sign > 0:
                q = self.stop
            b = born(q)
            if b is None:
                return False
            if b:
                hi = q
            else:
                lo, step = q, 2 * step
        if hi is None:
            return False
        while True:                          # bisect the birth to rounding
            mid = 0.5 * (lo + hi)
            if mid == lo or mid == hi:
                break
            if born(mid):
                hi = mid
            else:
                lo = mid
        pb = hi                             # the first value with rest points
        d = _splitting(prob.scene(pb), prob.winding, prob.rtol, prob.atol)
        if d == math.inf:                   # the saddle-node itself: its saddle just past it
            pb2 = pb + sign * 1e-13 * scale
            d = _splitting(prob.scene(pb2), prob.winding, prob.rtol, prob.atol)
        if d is None:
            return False                    # undecided (the manifolds not both graphs there)
        if d <= 0:
            kind, pe = "snic", pb
        else:
            # the running orbit outlives the birth: the homoclinic torque lies within 1e-6 past it, or the
            # branch goes on to it
            a, da, q, dq, width = pb, d, None, None, 1e-13 * scale
            while width <= 1e-6 * scale:
                x = pb + sign * width
                dx = _splitting(prob.scene(x), prob.winding, prob.rtol, prob.atol)
                if dx is None or dx <= 0:
                    q, dq = x, (-1.0 if dx is None else dx)
                    break
                a, da, width = x, dx, 4 * width
            if q is None:
                return False

            def g(x):
                d = _splitting(prob.scene(x), prob.winding, prob.rtol, prob.atol)
                return (-1.0 if d is None else d), None
            pe, _, _, _ = _root(g, a, da, q, dq, xtol=1e-14 * scale)
            kind = "homoclinic"
        # approach the end: the distance divided by up to 4 at each point (less where Newton needs it),
        # to 1e-6 of it
        Uc, n, f = U.copy(), np.array([0.0, 0.0, 1.0]), 0.25
        dist = abs(p - pe)
        while dist > 1e-6 * scale and f < 0.95:
            new = dist * f
            Upred = Uc.copy()
            Upred[1] = Uc[1] * math.sqrt(dist / new) if kind == "snic" else Uc[1] + math.log(dist / new)
            Upred[2] = pe - sign * new
            try:
                Un, evn, _ = self.correct(prob, Upred, n, np.array([0.0, 0.0, Upred[2]]), maxit=20)
            except (NewtonError, FlowError):
                f = math.sqrt(f)
                continue
            self.record(prob, Un, evn)
            Uc, dist, f = Un, new, max(0.25, f * f)
        sc = prob.scene(pe)
        eqs = [e for e in equilibria(sc) if e.kind in ("saddle", "saddle-node")]
        theta = eqs[0].theta if eqs else math.nan
        self.bifs.append(Bifurcation(kind, float(pe), math.inf, theta, 0.0, np.array([1.0, 0.0], dtype=complex),
                                     *self._where(prob, pe)))
        if kind == "snic":
            self.end = (f"snic at {self.param} = {float(pe)!r}: the rest points are born on the running orbit "
                        "(a saddle-node on an invariant circle); the period diverges")
        else:
            self.end = f"homoclinic at {self.param} = {float(pe)!r}: the period diverges"
        return True


def continue_orbit(scene: Scene, guess: tuple[float, float], param: str, stop: float, *, k: int = 1,
                   winding: int = 0, follow: str = "branch", step: float | None = None) -> Branch:
    """A periodic orbit followed in one scene field by pseudo-arclength continuation, with its bifurcations.

    From the orbit Newton's method finds at ``guess`` (as :func:`periodic_orbit`),
    the branch is followed until ``param`` reaches ``stop``, through turning
    points (folds).  A driven scene's orbit is a fixed point of the k-fold
    stroboscopic map advancing ``winding`` turns; an autonomous scene's (torque
    and damping, no drive) is a running orbit on the section ``theta = guess[0]``
    with its period as an unknown.  Along the branch the Floquet multipliers
    are watched; each bifurcation is located by solving its test function's
    root along the branch (to about 1e-12 in the parameter), not by the step,
    and only where the test function's sign is decided on both sides (beyond
    its error, about 1e-10 (1 + norm(M))^2: a change below it, as of the
    multipliers 1 +- 1e-8 i of a very fast drive, is no bifurcation).  The
    branch ends at ``stop`` exactly (never stepping past it: a field's edge,
    such as ``damping = 0``, may lie there):

    * ``'fold'``: a multiplier through +1 where the branch turns;
    * ``'pitchfork'``: through +1 where the symmetric orbit of an untorqued drive,
      ``(theta, v, t) -> (-theta, -v, t + T/2)``, breaks its symmetry (met from
      the asymmetric orbit, where the branch turns with no multiplier through
      +1, it is solved on the symmetric orbit);
    * ``'period-doubling'``: through -1;
    * ``'neimark-sacker'``: a complex pair through the unit circle;
    * ``'homoclinic'``: the period of an autonomous running orbit diverges where
      it meets the saddle (the retrapping torque of the damped pendulum);
    * ``'snic'``: the period of an autonomous running orbit diverges where a
      saddle and a node are born on it (a saddle-node on an invariant circle:
      the damped pendulum's torque 1 above the damping where the retrapping
      torque reaches 1), located at the rest points' birth to rounding.

    With ``follow='stable'`` the attracting orbit is followed: at a pitchfork
    or a period doubling where the branch loses stability the call switches to
    the stable child (period 2k after a doubling), so one call traces the
    route from a period-1 orbit through the cascade; at a fold, a subcritical
    bifurcation or a Neimark-Sacker point the attracting orbit ends and so does
    the branch (``Branch.end`` says why).  Ctrl-C stops the call.

    Parameters
    ----------
    scene : Scene
        A rigid pendulum in the uniform field: driven (``drive_amplitude`` and
        ``drive_frequency`` non-zero) or autonomous (no drive, a torque).
    guess : (float, float)
        A state ``(theta, v)`` near the orbit at the start.
    param : str
        The numeric scene field to move (``'drive_amplitude'``, ``'drive_frequency'``,
        ``'damping'``, ``'torque'``, ``'eps'``, ...).
    stop : float
        The value of ``param`` to continue to.
    k : int, optional
        The period in drive periods (driven scenes; default 1).
    winding : int, optional
        Turns per period (default 0; an autonomous running orbit takes the sign of ``guess[1]``).
    follow : {'branch', 'stable'}, optional
        Follow the one branch through everything (default), or the attracting orbit.
    step : float, optional
        The first arclength step (default ``min(0.05, |stop - start| / 20)``); steps adapt,
        between the parameter's resolution ``1e-10 max(1, |start|, |stop|)`` and 4 ``step``.

    Returns
    -------
    Branch
        The points, their multipliers and stability, and the bifurcations.

    Raises
    ------
    TypeError
        If ``param`` is not a string or an argument is not of its kind.
    ValueError
        If ``param`` is not a numeric scene field or does not change the orbit,
        ``stop`` equals the start, lies within the parameter's resolution of it
        (1e-10 of its size) or beyond 0 of the drive, ``step`` is below that
        resolution or too short to reach ``stop`` within the work limit of
        20000 points, the scene has dry friction (its monodromy jumps where
        v = 0), the guess does not converge (the message says where Newton
        got), or ``follow='stable'`` starts on an unstable orbit.
    ContinuationError
        A ValueError: the branch cannot be continued (a step shrank to nothing,
        say at a fold it cannot pass); its ``branch`` holds the part traced.
    NotImplementedError
        For the flexible cord, the cycloidal guide and the non-uniform fields.

    See Also
    --------
    periodic_orbit : one orbit by Newton's method.
    bifurcation_tree : every branch born on this one (both children of a pitchfork, the child of a
        period doubling), to a depth.
    continue_equilibria : the rest points against a parameter.

    Examples
    --------
    The damped driven pendulum's symmetric orbit breaks its symmetry, then doubles its period:

    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
    >>> br = pendula.continue_orbit(sc, (0.1, 1.9), "drive_amplitude", 1.075, follow="stable")
    >>> [(b.kind, b.period, round(b.value, 8)) for b in br.bifurcations]
    [('pitchfork', 1.0, 1.00431948), ('period-doubling', 1.0, 1.06637286)]
    """
    if follow not in ("branch", "stable"):
        raise ValueError(f"follow must be 'branch' or 'stable', got {follow!r:.40} (every branch met, to a "
                         "depth: pendula.bifurcation_tree)")
    tracer, prob, U, ev, t = start(scene, guess, param, stop, k, winding, follow, step)
    while True:
        out = tracer.run_segment(prob, U, ev, t)
        if out is None:
            break
        _, kind, prob_s, Us, evs, ts = out
        sw = tracer.switch(kind, prob_s, Us, evs, ts)
        if sw is None:
            break
        prob, U, ev, t = sw
    return tracer.branch()


def start(scene: Scene, guess, param, stop, k, winding, follow: str, step):
    """The arguments checked and the first point of a continuation: (tracer, problem, U, Evaluation,
    tangent towards stop), the point recorded."""
    require(scene, "continue_orbit", over=(param,))      # the capability table: noise and dry friction refused by name
    p0 = _param_value(scene, param)
    stop = _stop_value(scene, param, p0, stop)
    k = _checks.count(k, "k", 1, 10**4)
    winding = _checks.count(winding, "winding", -10**9, 10**9)
    if step is not None:
        step = _checks.real(step, "step", 0.0, lo_open=True)
    _check_steps(param, p0, stop, step)
    x0 = check_guess(guess, scene)
    # the one definition of a periodically forced scene (a drive, a vibrating pivot, or both at one frequency)
    driven = time_scales(scene).forcing_status != 1
    tracer = _Tracer(scene, param, p0, stop, follow, step)
    if driven:
        drive_period(scene, k)
        prob = OrbitProblem(scene, "map", k, winding, param)
        u0 = x0
    else:
        if scene.drive_amplitude != 0.0 or scene.drive_frequency != 0.0:
            raise ValueError("drive_frequency: a drive of frequency 0 is a constant torque; give it as torque")
        if param == "drive_amplitude":
            raise ValueError("param: continuing drive_amplitude from 0 turns the autonomous scene into a driven "
                             "one; start from a driven scene (drive_amplitude and drive_frequency non-zero)")
        if x0[1] == 0.0:
            raise ValueError("guess: an autonomous running orbit needs a velocity (guess[1] != 0)")
        w = winding or (1 if x0[1] > 0 else -1)
        if abs(w) != 1:
            raise ValueError(f"winding: an autonomous running orbit turns once a period (+-1), got {winding}")
        prob = OrbitProblem(scene, "section", 1, w, param, theta_s=float(x0[0]))
        T0 = _first_return(scene, x0, w, prob.rtol, prob.atol)
        u0 = np.array([x0[1], T0])
    try:
        u, _, ev, _ = newton(prob, u0, p0, _TOL, 100)
    except NewtonError as exc:
        raise ValueError(f"guess: Newton's iteration for the starting orbit at {param} = {p0!r} failed: {exc}; it "
                         f"got to {tuple(float(x) for x in exc.state[0])} with residual {exc.residual:.3g}") from None
    if driven and scene.pivot_amplitude == 0.0 and scene.torque == 0.0 and param != "torque" and winding == 0 \
            and k % 2 == 1:
        # the symmetric orbit of an untorqued drive: follow it on the half-period map
        T = drive_period(scene, k)
        end, _, _ = flow(scene, u, [0.5 * T], prob.rtol, prob.atol)
        m = round((end[0, 0] + u[0]) / (2 * math.pi))
        if max(abs(2 * math.pi * m - end[0, 0] - u[0]), abs(end[0, 1] + u[1])) < 1e-6:
            half = OrbitProblem(scene, "half", k, 0, param, m=m)
            try:
                u, _, ev, _ = newton(half, u, p0, _TOL, 20)
                prob = half
            except NewtonError:
                pass
    U = np.append(u, p0)
    t, Fp = tracer.tangent(prob, U, ev)
    if not np.any(Fp):
        raise ValueError(f"param: the orbit does not depend on {param!r} (changing it does not change the flow)")
    if t[2] == 0.0:
        raise ContinuationError(f"{param}: the starting orbit sits on a fold; start a little away from it")
    if (t[2] > 0) != (stop > p0):
        t = -t
    if follow == "stable" and not _stable(prob.mode, ev):
        raise ValueError("follow: the orbit at guess is unstable; follow='stable' starts from an attracting orbit")
    tracer.record(prob, U, ev)
    return tracer, prob, U, ev, t
