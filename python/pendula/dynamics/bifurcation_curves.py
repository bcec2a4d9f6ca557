"""Codimension two: a fold or a period doubling of a periodic orbit followed in two scene fields.

A bifurcation located by :func:`~pendula.continue_orbit` is a point where the
stroboscopic map's monodromy ``M`` has the multiplier ``lam`` (+1 at a fold of
cycles, -1 at a period doubling).  With a second field free, the points where
this holds form a curve in the plane of the two fields.  It is followed here by
pseudo-arclength continuation of the minimally augmented system (Govaerts,
*Numerical Methods for Bifurcations of Dynamical Equilibria*, section 4.4;
Kuznetsov, *Elements of Applied Bifurcation Theory*, section 10.2.2): four
unknowns, the section point ``x`` and the two fields ``(p1, p2)``, and three
equations,

    P(x; p1, p2) - x - (2 pi winding, 0) = 0,    g(x; p1, p2) = 0,

``g`` the bordered test function: the last component of the solution of
``[[M - lam I, b], [c^T, 0]] (w, g) = (0, 1)``, with ``b`` and ``c`` the left and
right singular vectors of ``M - lam I`` at the last point of the curve (so the
bordered matrix stays regular while ``M - lam I`` is singular, and ``g``
vanishes exactly where it is).  The fourth equation fixes the arclength along
the curve's tangent.  The flow and ``M`` come from the one Newton-and-monodromy
core (:func:`.periodic.flow`); the derivatives of ``g`` and of ``P`` in the
fields are differences of flows (they steer Newton; the points do not depend on
them).

On the way the curve's codimension-two points are detected by the sign of
their test functions and located on the curve (Kuznetsov, sections 8.7 and 9.2;
Kuznetsov & Meijer, *SIAM J. Sci. Comput.* 26, 2005): on a fold curve the cusp
(the fold's quadratic normal-form coefficient ``a`` vanishes), fold-flip (the
other multiplier through -1) and the 1:1 resonance (through +1); on a
period-doubling curve the generalized period doubling (the cubic coefficient
``c`` vanishes), fold-flip (the other multiplier through +1) and the 1:2
resonance (through -1).  The normal-form coefficients come from central
differences of the monodromy along the critical eigenvector.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _checks
from ..scene import Scene, SceneError
from ..systems.contract import require, time_scales
from .branches import Bifurcation, ContinuationError
from .branch_functions import _root
from .continuation import _param_value
from .homoclinic_curves import homoclinic_rows
from .periodic import FlowError, drive_period, flow, multipliers_of, reduce_angle

__all__ = ["BifurcationCurve", "CodimTwoPoint", "continue_bifurcation", "CURVE_KINDS"]

#: The bifurcations a curve can follow, and the multiplier each is defined by.
CURVE_KINDS = {"fold": 1.0, "period-doubling": -1.0, "pitchfork": 1.0}
#: The most points of one curve (the work limit).
MAX_POINTS = 5_000
_TOL = 1e-11           # the residual a corrected point meets (the flow's own accuracy is about 1e-12)
_RTOL = _ATOL = 1e-12  # the flow's tolerances
_MAXIT = 8             # corrector iterations before the step is halved


@dataclass(frozen=True)
class CodimTwoPoint:
    """A codimension-two point on a bifurcation curve, located where its test function changes sign.

    Attributes
    ----------
    kind : str
        ``'cusp'`` (a fold curve's quadratic normal-form coefficient vanishes), ``'generalized
        period-doubling'`` (a period-doubling curve's cubic coefficient vanishes: the doubling turns
        from super- to subcritical), ``'fold-flip'`` (multipliers +1 and -1), ``'1:1 resonance'``
        (a double +1), ``'1:2 resonance'`` (a double -1).
    values : tuple of float
        The two fields there, ``(first, second)`` as the curve's ``params``.
    theta, v : float
        The orbit's state on its section.
    multipliers : numpy.ndarray
        The Floquet multipliers there.

    See Also
    --------
    continue_bifurcation : finds them.

    Examples
    --------
    >>> import numpy as np, pendula
    >>> pt = pendula.CodimTwoPoint("cusp", (0.4, 0.8), 0.1, 0.2, np.array([1.0, 0.05]))
    >>> pt
    CodimTwoPoint('cusp' at (0.4, 0.8), theta=0.1, v=0.2, |multipliers|=[1, 0.05])
    """

    kind: str
    values: tuple
    theta: float
    v: float
    multipliers: np.ndarray

    def __repr__(self) -> str:
        mods = ", ".join(f"{abs(complex(m)):.4g}" for m in np.ravel(self.multipliers))
        return (f"CodimTwoPoint({self.kind!r} at ({self.values[0]:.10g}, {self.values[1]:.10g}), "
                f"theta={self.theta:.6g}, v={self.v:.6g}, |multipliers|=[{mods}])")


@dataclass(frozen=True)
class BifurcationCurve:
    """A fold or period-doubling curve in the plane of two scene fields (:func:`continue_bifurcation`).

    Attributes
    ----------
    scene : Scene
        The scene the curve started from (the bifurcation's).
    kind : str
        ``'fold'`` (a multiplier +1), ``'period-doubling'`` (-1) or ``'pitchfork'`` (+1 where the symmetric
        orbit of an untorqued drive breaks its symmetry: followed as the flip of the half-period map, its
        ``coefficient`` that flip's, positive where the pitchfork is supercritical), or ``'homoclinic'``
        (the retrapping point of a running autonomous orbit: ``theta`` the saddle's angle, ``v`` 0, the
        multipliers and coefficient NaN).
    params : tuple of str
        The two fields: the one the bifurcation was found in, and the second.
    first, second : numpy.ndarray
        The two fields at each point of the curve.
    theta, v : numpy.ndarray
        The orbit's state on its section at each point (theta in ``[-pi, pi]``).
    period : int
        The orbit's period in drive periods.
    winding : int
        Its turns per period.
    multipliers : numpy.ndarray
        The two Floquet multipliers at each point (complex, shape (points, 2), largest modulus first).
    coefficient : numpy.ndarray
        The normal-form coefficient at each point: ``a`` of a fold (``x -> x + a x^2`` on the centre
        manifold; its sign is that of the critical eigenvector's orientation, kept continuous along the
        curve), ``c`` of a period doubling (``x -> -x + c x^3``, Kuznetsov's sign: positive where the
        doubling is supercritical).
    points : tuple of CodimTwoPoint
        The codimension-two points met, in order.
    end : str
        Why the curve ends: ``'stop'`` when ``second`` reached ``stop``, or the edge of a field's range, a
        turn back to where it started, the work limit.

    See Also
    --------
    continue_bifurcation : makes it.

    Examples
    --------
    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
    >>> br = pendula.continue_orbit(sc, (0.1, 1.9), "drive_amplitude", 1.07, follow="stable")
    >>> pd = br.bifurcations[-1]
    >>> curve = pendula.continue_bifurcation(pd, "drive_frequency", 0.67, step=0.002)
    >>> curve.end, curve.params
    ('stop', ('drive_amplitude', 'drive_frequency'))
    """

    scene: Scene
    kind: str
    params: tuple
    first: np.ndarray
    second: np.ndarray
    theta: np.ndarray
    v: np.ndarray
    period: int
    winding: int
    multipliers: np.ndarray
    coefficient: np.ndarray
    points: tuple
    end: str

    def __repr__(self) -> str:
        n = len(self.first)
        span = ""
        if n:
            span = (f" from ({self.first[0]:.6g}, {self.second[0]:.6g}) to "
                    f"({self.first[-1]:.6g}, {self.second[-1]:.6g})")
        pts = "; ".join(f"{p.kind} at ({p.values[0]:.6g}, {p.values[1]:.6g})" for p in self.points[:4])
        if len(self.points) > 4:
            pts += f"; and {len(self.points) - 4} more"
        return (f"BifurcationCurve({self.kind} in ({self.params[0]}, {self.params[1]}){span}, {n} points, "
                f"codim-2 [{pts}], end={self.end!r})")

    def __len__(self) -> int:
        return len(self.first)


# ---------------------------------------------------------------- the augmented system


class _Point:
    """One evaluation at z = (theta, v, p1, p2): the map's residual F, the monodromy M, the test g."""

    __slots__ = ("z", "F", "M", "g")

    def __init__(self, z, F, M, g):
        self.z, self.F, self.M, self.g = z, F, M, g


class _System:
    """The augmented system of one curve: the scene family in two fields, the multiplier, the borders."""

    def __init__(self, scene: Scene, p1: str, p2: str, lam: float, k: int, winding: int, half_m: int | None = None):
        self.base, self.p1, self.p2, self.lam, self.k, self.winding = scene, p1, p2, lam, k, winding
        # a pitchfork: the symmetric orbit as a fixed point of the half-period map
        # G(x) = (2 pi m - theta(T/2), -v(T/2)) (G o G = P), where the pitchfork of P is G's flip
        self.half_m = half_m
        self.b = self.c = self.q = None
        self._cache: tuple | None = None

    def scene(self, a: float, b: float) -> Scene:
        if self._cache is not None and self._cache[0] == (a, b):
            return self._cache[1]
        try:
            sc = self.base.replace(**{self.p1: float(a), self.p2: float(b)})
        except SceneError as exc:
            raise FlowError(f"outside a field's range ({exc})") from None
        self._cache = ((a, b), sc)
        return sc

    def map(self, x, a: float, b: float):
        """(F, M) at the section point x: the residual and the monodromy of the map (of G: DG, for a pitchfork)."""
        sc = self.scene(a, b)
        try:
            T = drive_period(sc, self.k)
        except ValueError as exc:
            raise FlowError(str(exc)) from None
        if self.half_m is not None:
            end, mono, _ = flow(sc, x, [0.5 * T], _RTOL, _ATOL)
            F = np.array([2 * math.pi * self.half_m - end[0, 0] - x[0], -end[0, 1] - x[1]])
            return F, -mono[0]
        end, mono, _ = flow(sc, x, [T], _RTOL, _ATOL)
        F = end[0] - np.asarray(x, dtype=float) - np.array([2 * math.pi * self.winding, 0.0])
        return F, mono[0]

    def set_borders(self, M) -> None:
        """b and c: the left and right singular vectors of M - lam I of its smallest singular value."""
        U, _, Vt = np.linalg.svd(M - self.lam * np.eye(2))
        self.b, self.c = U[:, -1].copy(), Vt[-1].copy()
        mu, V = np.linalg.eig(M)
        q = np.real(V[:, int(np.argmin(np.abs(mu - self.lam)))])
        q = q / np.linalg.norm(q)
        self.q = -q if self.q is not None and np.dot(q, self.q) < 0 else q

    def test(self, M) -> float:
        """The bordered test function g of M (0 exactly where M - lam I is singular)."""
        B = np.zeros((3, 3))
        B[:2, :2] = M - self.lam * np.eye(2)
        B[:2, 2], B[2, :2] = self.b, self.c
        return float(np.linalg.solve(B, np.array([0.0, 0.0, 1.0]))[2])

    def evaluate(self, z) -> _Point:
        z = np.asarray(z, dtype=float)
        F, M = self.map(z[:2], z[2], z[3])
        return _Point(z, F, M, self.test(M))

    def residual(self, pt: _Point) -> np.ndarray:
        return np.append(pt.F, pt.g)

    def jacobian(self, pt: _Point) -> np.ndarray:
        """The 3 x 4 Jacobian of (F, g): F's in the state exact (M - I), the rest by forward differences."""
        J = np.zeros((3, 4))
        J[:2, :2] = pt.M - np.eye(2)
        base = self.residual(pt)
        for j in range(4):
            h = 1e-7 * max(1.0, abs(pt.z[j]))
            zh = pt.z.copy()
            zh[j] += h
            try:
                col = (self.residual(self.evaluate(zh)) - base) / h
            except FlowError:          # at the edge of a field's range: the backward difference
                zh[j] = pt.z[j] - h
                col = (base - self.residual(self.evaluate(zh))) / h
            if j < 2:
                J[2, j] = col[2]
            else:
                J[:, j] = col
        return J


def _null(J, previous=None) -> np.ndarray:
    """The unit null vector of the 3 x 4 Jacobian, oriented along previous."""
    t = np.linalg.svd(J)[2][-1]
    if previous is not None and np.dot(t, previous) < 0:
        t = -t
    return t


def _converged(sys_: _System, pt: _Point) -> bool:
    scale = 1.0 + float(np.max(np.abs(pt.z[:2])))
    return float(np.max(np.abs(pt.F))) <= _TOL * scale and abs(pt.g) <= _TOL * (1.0 + float(np.linalg.norm(pt.M)))


def _correct(sys_: _System, z, n, z0, maxit: int = _MAXIT) -> tuple[_Point, np.ndarray]:
    """Newton on (F, g, n . (z - z0)) = 0 from z; FlowError when it fails.  Returns the point and its
    Jacobian (of the last iteration)."""
    z = np.asarray(z, dtype=float)
    pt = sys_.evaluate(z)
    last = math.inf
    for _ in range(maxit):
        J = sys_.jacobian(pt)
        A = np.vstack([J, n])
        r = np.append(sys_.residual(pt), np.dot(n, z - z0))
        try:
            d = np.linalg.solve(A, -r)
        except np.linalg.LinAlgError:
            raise FlowError("the augmented system is singular") from None
        if not np.all(np.isfinite(d)):
            raise FlowError("the Newton step is not finite")
        if np.max(np.abs(d[:2])) > 0.5:
            raise FlowError("the Newton step left the neighbourhood of the curve")
        z = z + d
        pt = sys_.evaluate(z)
        step = float(np.max(np.abs(d)))
        if _converged(sys_, pt) and (step <= 1e-7 * (1 + float(np.max(np.abs(z)))) or last <= 1e-7):
            return pt, J
        last = step
    raise FlowError(f"no convergence in {maxit} iterations")


# ---------------------------------------------------------------- the codimension-two test functions


def _normal_form(sys_: _System, pt: _Point) -> float:
    """The normal-form coefficient at a point of the curve: a = <p, B(q, q)> / 2 of a fold, c = <p, C(q, q,
    q)> / 6 + <p, B(q, (I - A)^-1 B(q, q))> / 2 of a period doubling (Kuznetsov & Meijer 2005; A the
    monodromy, q and p its right and left eigenvectors of lam, <p, q> = 1), B and C by central
    differences of the monodromy along q; NaN where a flow fails."""
    M, lam, x, a_, b_ = pt.M, sys_.lam, pt.z[:2], pt.z[2], pt.z[3]
    mu, V = np.linalg.eig(M)
    if abs(float(np.trace(M)) - 2 * lam) < 1e-6:
        return math.nan          # a double multiplier (a 1:1 or 1:2 resonance): no codim-1 normal form
    q = np.real(V[:, int(np.argmin(np.abs(mu - lam)))])
    q = q / np.linalg.norm(q)
    # a's sign follows q's orientation (B(q, q) is even in q, p odd): q is kept continuous along the curve
    if sys_.q is not None and np.dot(q, sys_.q) < 0:
        q = -q
    muT, W = np.linalg.eig(M.T)
    p = np.real(W[:, int(np.argmin(np.abs(muT - lam)))])
    p = p / np.dot(p, q)
    try:
        if lam > 0:
            h = 1e-4
            Mp, Mm = sys_.map(x + h * q, a_, b_)[1], sys_.map(x - h * q, a_, b_)[1]
            return 0.5 * float(p @ ((Mp - Mm) @ q)) / (2 * h)
        h = 2e-3
        Mp, Mm = sys_.map(x + h * q, a_, b_)[1], sys_.map(x - h * q, a_, b_)[1]
        Bqq = (Mp - Mm) @ q / (2 * h)
        Cqqq = (Mp - 2 * M + Mm) @ q / (h * h)
        r = np.linalg.solve(np.eye(2) - M, Bqq)
        hr = 1e-4 / max(1e-300, float(np.linalg.norm(r)))
        Bqr = (sys_.map(x + hr * r, a_, b_)[1] - sys_.map(x - hr * r, a_, b_)[1]) @ q / (2 * hr)
        return float(p @ Cqqq) / 6.0 + 0.5 * float(p @ Bqr)
    except (FlowError, np.linalg.LinAlgError):
        return math.nan


def _tests(sys_: _System, pt: _Point, coefficient: float) -> dict:
    """The codimension-two test functions at a point of the curve (each changes sign at its point): the
    normal-form coefficient, and the other multiplier mu2 = tr M - lam through -1 and +1."""
    tr = float(np.trace(pt.M))
    if sys_.lam > 0:
        return {"cusp": coefficient, "fold-flip": tr, "1:1 resonance": tr - 2.0}
    return {"generalized period-doubling": coefficient, "fold-flip": tr, "1:2 resonance": tr + 2.0}


def _test_errors(sys_: _System, pt: _Point) -> dict:
    """The error of each test function (below it, its sign is not decided): the multipliers' from the
    flow's error as continuation's (100 rtol (1 + norm M)^2), the coefficients' from their differences
    (truncation h^2 and rounding rtol / h or rtol / h^2 of the central differences, times the size of M)."""
    nM = 1.0 + float(np.linalg.norm(pt.M))
    em = 100.0 * _RTOL * nM ** 2
    if sys_.lam > 0:
        return {"cusp": 1e-6 * nM ** 2, "fold-flip": em, "1:1 resonance": em}
    return {"generalized period-doubling": 1e-4 * nM ** 3, "fold-flip": em, "1:2 resonance": em}


#: The codimension-two points of G's flip curve, named as points of the pitchfork curve of P.
_HALF_NAMES = {"generalized period-doubling": "degenerate pitchfork", "fold-flip": "fold-pitchfork",
               "1:2 resonance": "1:1 resonance"}


def _signs(values: dict, errors: dict) -> dict:
    return {k: (0 if not math.isfinite(v) or abs(v) <= errors[k] else (1 if v > 0 else -1))
            for k, v in values.items()}


# ---------------------------------------------------------------- the tracer


def _field_edge(scene: Scene, name: str, value: float) -> tuple[float, float]:
    """The range (lo, hi) of a field on the side of its value: the drive's fields never cross 0 (there the
    scene is no longer driven), another field stops at 0 where the scene refuses the other side."""
    lo, hi = -math.inf, math.inf
    if name in ("drive_amplitude", "drive_frequency") or value == 0.0:
        zero_edge = True
    else:
        try:
            scene.replace(**{name: -value})
            zero_edge = False
        except SceneError:
            zero_edge = True
    if zero_edge and value != 0.0:
        lo, hi = (0.0, math.inf) if value > 0 else (-math.inf, 0.0)
    return lo, hi


class _Curve:
    """The state of one continue_bifurcation call."""

    def __init__(self, sys_: _System, stop: float, step: float | None, edges1, p2_start: float):
        self.sys, self.stop = sys_, stop
        span = abs(stop - p2_start)
        self.h0 = step if step is not None else min(0.05, span / 20)
        self.hmax = max(self.h0, span / 10) if step is None else 4 * step
        self.hmin = 1e-10 * max(1.0, abs(p2_start), abs(stop))
        self.lo2, self.hi2 = sorted((p2_start, stop))
        self.lo1, self.hi1 = edges1
        self.rows: list = []
        self.points: list = []
        self.end = ""

    def record(self, pt: _Point, coefficient: float) -> None:
        mu = multipliers_of(pt.M if self.sys.half_m is None else pt.M @ pt.M)
        self.rows.append((float(pt.z[2]), float(pt.z[3]), reduce_angle(pt.z[0]), float(pt.z[1]), mu[0], mu[1],
                          coefficient))

    def curve(self, scene, kind, params, k, winding) -> BifurcationCurve:
        r = self.rows
        col = (lambda i: np.array([x[i] for x in r], dtype=float))
        mus = np.array([[x[4], x[5]] for x in r], dtype=complex).reshape(-1, 2)
        return BifurcationCurve(scene, kind, params, col(0), col(1), col(2), col(3), k, winding, mus, col(6),
                                tuple(self.points), self.end)

    def clip(self, z, t, h):
        """The predictor z + h t, shortened so that neither field passes its edge (the stop, the start, or the
        end of a field's range); returns (prediction, the edge's (index, value) or None)."""
        zp = z + h * t
        hit = None
        for idx, lo, hi in ((3, self.lo2, self.hi2), (2, self.lo1, self.hi1)):
            if t[idx] != 0.0 and not lo <= zp[idx] <= hi:
                edge = hi if zp[idx] > hi else lo
                hh = (edge - z[idx]) / t[idx]
                if hh < h:
                    h, hit = hh, (idx, edge)
                    zp = z + h * t
                    zp[idx] = edge
        return zp, hit

    def run(self, pt: _Point, t: np.ndarray, coefficient: float) -> None:
        sys_ = self.sys
        h = self.h0
        tests = _tests(sys_, pt, coefficient)
        self.signs = _signs(tests, _test_errors(sys_, pt))
        while True:
            if len(self.rows) >= MAX_POINTS:
                self.end = f"work limit: {MAX_POINTS} points"
                return
            zp, hit = self.clip(pt.z, t, h)
            try:
                if hit is not None:            # the last point exactly on the edge
                    n = np.zeros(4)
                    n[hit[0]] = 1.0
                    ptb, Jb = _correct(sys_, zp, n, zp)
                    ptb.z[hit[0]] = hit[1]
                else:
                    ptb, Jb = _correct(sys_, zp, t, zp)
                tb = _null(Jb, t)
            except FlowError as exc:
                if hit is not None and hit[0] == 2:
                    # the field's end is open (no scene there, as a drive of amplitude 0): the curve ends
                    # at its last point before it
                    self.end = (f"edge: {sys_.p1} reaches {hit[1]!r}, the end of its range (last point at "
                                f"{float(pt.z[2])!r})")
                    return
                h *= 0.5
                if h < self.hmin:
                    self.end = (f"the curve cannot be continued past ({sys_.p1}, {sys_.p2}) = "
                                f"({float(pt.z[2])!r}, {float(pt.z[3])!r}): {exc}; the step shrank below "
                                f"{self.hmin:.1e}")
                    return
                continue
            if hit is None and np.dot(t, tb) < 0.98 and h > 1e3 * self.hmin:
                h *= 0.5
                continue
            coef_b = _normal_form(sys_, ptb)
            tests_b = _tests(sys_, ptb, coef_b)
            self.events(pt, t, tests, ptb, tests_b)
            self.record(ptb, coef_b)
            sys_.set_borders(ptb.M)
            if hit is not None:
                idx, edge = hit
                if idx == 3 and edge == self.stop:
                    self.end = "stop"
                elif idx == 3:
                    self.end = f"turned back to {sys_.p2} = {edge!r} (where it started)"
                else:
                    self.end = f"edge: {sys_.p1} = {edge!r}, the end of its range"
                return
            big = float(np.max(np.abs(multipliers_of(ptb.M))))
            if big > 1e6:
                self.end = (f"a multiplier reaches {big:.1e} at ({sys_.p1}, {sys_.p2}) = ({float(ptb.z[2])!r}, "
                            f"{float(ptb.z[3])!r}): too unstable for single shooting")
                return
            h = min(1.5 * h, self.hmax)
            pt, t, tests = ptb, tb, tests_b

    def events(self, pa: _Point, ta, tests_a: dict, pb: _Point, tests_b: dict) -> None:
        """The codimension-two points between two points of the curve, located on it."""
        sys_ = self.sys
        signs_b = _signs(tests_b, _test_errors(sys_, pb))
        changed = [key for key, sgn in signs_b.items() if sgn and self.signs.get(key) and sgn != self.signs[key]]
        for key, sgn in signs_b.items():
            if sgn:
                self.signs[key] = sgn
        sb = float(np.dot(ta, pb.z - pa.z))
        found = []
        for key in changed:
            if not (tests_a[key] > 0) != (tests_b[key] > 0) or sb == 0.0:
                found.append((0.0, key, pa, tests_a[key]))
                continue

            def g(s, key=key):
                zp = pa.z + (s / sb) * (pb.z - pa.z)
                pc, _ = _correct(sys_, zp, ta, pa.z + s * ta, maxit=20)
                coef = _normal_form(sys_, pc) if key in ("cusp", "generalized period-doubling") else 0.0
                return _tests(sys_, pc, coef)[key], pc
            try:
                s, pc, _, _ = _root(g, 0.0, tests_a[key], sb, tests_b[key], xtol=1e-12 * (1 + abs(sb)), maxit=60)
            except FlowError:
                s, pc = 0.0, pa
            found.append((s, key, pc, None))
        half = sys_.half_m is not None
        for _, key, pc, _ in sorted(found, key=lambda e: e[0]):
            self.points.append(CodimTwoPoint(_HALF_NAMES.get(key, key) if half else key,
                                             (float(pc.z[2]), float(pc.z[3])), reduce_angle(pc.z[0]),
                                             float(pc.z[1]), multipliers_of(pc.M @ pc.M if half else pc.M)))


def _symmetric(point: Bifurcation, scene: Scene, k: int, p2: str) -> int:
    """The m of the half-period map G whose fixed point is the pitchfork's symmetric orbit; errors where the
    scene or the second field breaks the drive's symmetry (theta, v, t) -> (-theta, -v, t + T/2)."""
    if p2 in ("torque", "pivot_amplitude"):
        raise ValueError(f"second_param: {p2!r} breaks the symmetry (theta, v, t) -> (-theta, -v, t + T/2) of "
                         "the pitchfork; in it the pitchfork unfolds and is no curve")
    if scene.torque != 0.0 or scene.pivot_amplitude != 0.0 or point.winding != 0 or k % 2 == 0:
        raise NotImplementedError("point: a pitchfork without the drive's symmetry (a torque, a vibrating "
                                  "pivot, a running or even-period orbit) is not followed in two fields yet")
    x = np.array([point.theta, point.v])
    try:
        end, _, _ = flow(scene, x, [0.5 * drive_period(scene, k)], _RTOL, _ATOL)
    except (ValueError, FlowError) as exc:
        raise ContinuationError(f"point: the flow fails at the pitchfork: {exc}") from None
    m = round((end[0, 0] + x[0]) / (2 * math.pi))
    if max(abs(2 * math.pi * m - end[0, 0] - x[0]), abs(end[0, 1] + x[1])) > 1e-6:
        raise NotImplementedError("point: this pitchfork's orbit is not symmetric (a branch point without the "
                                  "drive's symmetry); it is not followed in two fields yet")
    return m


def continue_bifurcation(point: Bifurcation, second_param: str, stop: float, *,
                         step: float | None = None) -> BifurcationCurve:
    """A fold or a period doubling of a periodic orbit followed in two scene fields.

    The bifurcation ``point`` (as :func:`continue_orbit` reports it, in its field
    ``point.param``) lies on a curve in the plane of that field and
    ``second_param``; the curve is followed by pseudo-arclength continuation
    of the minimally augmented system: the section point and the two fields
    as unknowns, the periodic orbit's equations and the bordered test function
    of the monodromy (zero where it has the multiplier +1 of a fold or -1 of
    a period doubling) as equations (Govaerts, section 4.4), until
    ``second_param`` reaches ``stop``.  A curve that meets the end of a
    field's range (a drive's amplitude or frequency at 0, or a field that
    cannot be negative) or turns back to where it started ends there, exactly
    on the edge, and is returned with the reason in ``end``; so does a curve
    of 5000 points (the work limit: a fold curve that winds through the
    resonances of a slow drive can need more).  Ctrl-C stops the call.  On the way the
    codimension-two points are located where their test functions change
    sign (beyond the functions' error): a cusp, a generalized period
    doubling, fold-flip, 1:1 and 1:2 resonances (Kuznetsov, sections 8.7 and
    9.2; the damped pendulum's det M = exp(-damping T) < 1 rules out the
    last three, so only the first two occur there).

    Parameters
    ----------
    point : Bifurcation
        A ``'fold'``, ``'period-doubling'`` or ``'pitchfork'`` of a driven scene
        from :func:`continue_orbit` (a pitchfork of the symmetric orbit of an
        untorqued drive: followed as the flip of the half-period map ``G``,
        ``G o G = P``, where it is regular; its codimension-two points are
        named ``'degenerate pitchfork'``, ``'fold-pitchfork'``, ``'1:1 resonance'``),
        or a ``'homoclinic'`` of an autonomous running orbit (the retrapping
        torque: at each value of ``second_param`` the first field is solved
        for the zero of the splitting of the saddle's manifolds, as
        :func:`continue_orbit` locates it; the curve ends where the homoclinic
        orbit ceases, at the saddle-node on the circle).
    second_param : str
        The second numeric scene field (``'drive_frequency'``, ``'damping'``,
        ``'torque'``, ...), not the field the point was found in.
    stop : float
        The value of ``second_param`` to continue to.
    step : float, optional
        The first arclength step (default ``min(0.05, abs(stop - start) / 20)``);
        steps adapt up to 4 ``step``.

    Returns
    -------
    BifurcationCurve
        Both fields, the orbit and its multipliers along the curve, the
        normal-form coefficient, the codimension-two points and the end reason.

    Raises
    ------
    TypeError
        If ``point`` is not a Bifurcation or an argument is not of its kind.
    ValueError
        If ``second_param`` is not a numeric scene field, is the point's own
        field or does not change the orbit; if ``stop`` equals the start or
        lies outside the field's range; if ``point`` is of a kind that cannot
        be continued or carries no scene, or breaks the symmetry of a
        pitchfork (``torque``).
    NotImplementedError
        For a Neimark-Sacker point, an equilibrium's
        saddle-node or a pitchfork without the drive's symmetry (not followed
        in two fields yet).
    ContinuationError
        The start does not lie on a curve (Newton fails there).

    See Also
    --------
    continue_orbit : finds the bifurcations along one field.
    shapiro_tongue : the Shapiro steps' edges of a junction, as fold curves.

    Examples
    --------
    The first period doubling of the driven pendulum's cascade, followed in the drive's frequency:

    >>> import pendula
    >>> sc = pendula.Scene(damping=0.5, drive_amplitude=1.0, drive_frequency=2/3)
    >>> br = pendula.continue_orbit(sc, (0.1, 1.9), "drive_amplitude", 1.07, follow="stable")
    >>> pd = br.bifurcations[-1]
    >>> curve = pendula.continue_bifurcation(pd, "drive_frequency", 0.68)
    >>> curve.end, round(float(curve.first[-1]), 6)
    ('stop', 1.097246)
    """
    if not isinstance(point, Bifurcation):
        raise TypeError(f"point must be a Bifurcation from continue_orbit, not {type(point).__name__}")
    if point.kind in ("neimark-sacker", "saddle-node"):
        raise NotImplementedError(f"point: a {point.kind} is not followed in two fields yet (only "
                                  f"{', '.join(CURVE_KINDS)} curves)")
    if point.kind not in CURVE_KINDS and point.kind != "homoclinic":
        raise ValueError(f"point: a {point.kind!r} cannot be continued (only {' and '.join(CURVE_KINDS)})")
    if point.scene is None or point.param is None:
        raise ValueError("point: it carries no scene; pass a bifurcation as continue_orbit reports it")
    scene, p1 = point.scene, point.param
    p2 = second_param
    try:
        p2_start = _param_value(scene, p2)
    except (TypeError, ValueError) as exc:
        raise type(exc)(f"second_{exc}") from None       # the message names 'param'
    if p2 == p1:
        raise ValueError(f"second_param: {p2!r} is the field the bifurcation was found in; give another field")
    require(scene, "continue_orbit", over=(p1, p2))
    autonomous = time_scales(scene).forcing_status == 1
    if point.kind == "homoclinic" and not autonomous:
        raise ValueError("point: a homoclinic point of a driven scene is not a continue_orbit result")
    if autonomous and point.kind != "homoclinic":
        raise ValueError(f"point: the {point.kind} of an autonomous orbit is not a bifurcation of a driven scene's "
                         "map; only driven scenes' folds and period doublings are followed")
    stop = _checks.real(stop, "stop")
    if stop == p2_start:
        raise ValueError(f"stop: equals the scene's {p2} = {p2_start!r}; give the value to continue to")
    lo2, hi2 = _field_edge(scene, p2, p2_start)
    # the drive's edges are open (at 0 the scene is not driven), another field's closed (damping = 0)
    open_edges = p2 in ("drive_amplitude", "drive_frequency")
    inside = (lo2 < stop < hi2) if open_edges else (lo2 <= stop <= hi2)
    if not inside:
        raise ValueError(f"stop: {p2} = {stop!r} is outside the field's range on the scene's side "
                         f"({lo2!r}, {hi2!r})")
    try:
        scene.replace(**{p2: stop})
    except SceneError as exc:
        raise ValueError(f"stop: {exc}") from None
    if abs(stop - p2_start) < 1e-10 * max(1.0, abs(p2_start), abs(stop)):
        raise ValueError(f"stop: {stop!r} lies within the resolution of the scene's {p2} = {p2_start!r}")
    if step is not None:
        step = _checks.real(step, "step", 0.0, lo_open=True)
        if abs(stop - p2_start) / (4 * step) > MAX_POINTS:
            raise ValueError(f"step: {step!r} is too short to reach stop = {stop!r} within the work limit of "
                             f"{MAX_POINTS} points")
    if point.kind == "homoclinic":
        first, second, theta, end = homoclinic_rows(scene, p1, p2, point.value, p2_start, stop, step,
                                                    int(point.winding) or 1, MAX_POINTS)
        n = len(first)
        nan = np.full(n, math.nan)
        return BifurcationCurve(scene, "homoclinic", (p1, p2), first, second, theta, np.zeros(n), 0,
                                int(point.winding), np.full((n, 2), math.nan, dtype=complex), nan, (), end)
    k = int(round(point.period))
    lam = CURVE_KINDS[point.kind]
    half_m = _symmetric(point, scene, k, p2) if point.kind == "pitchfork" else None
    sys_ = _System(scene, p1, p2, -1.0 if half_m is not None else lam, k, int(point.winding), half_m)
    z0 = np.array([point.theta, point.v, float(getattr(scene, p1)), p2_start])
    try:
        pt = sys_.evaluate(z0)
    except FlowError as exc:
        raise ContinuationError(f"point: the flow fails at the bifurcation: {exc}") from None
    sys_.set_borders(pt.M)
    n = np.array([0.0, 0.0, 0.0, 1.0])         # corrected at the start's second field
    try:
        pt, J = _correct(sys_, z0, n, z0, maxit=20)
    except FlowError as exc:
        raise ContinuationError(f"point: no {point.kind} curve through it (Newton at {p2} = {p2_start!r}: "
                                f"{exc})") from None
    sys_.set_borders(pt.M)
    J = sys_.jacobian(pt)
    if not np.any(J[:, 3]):
        raise ValueError(f"second_param: the orbit does not depend on {p2!r} (changing it does not change the flow)")
    t = _null(J)
    if abs(t[3]) < 1e-8:
        raise ContinuationError(f"point: the {point.kind} curve turns in {p2} at the start; start a little away "
                                "from the turn")
    if (t[3] > 0) != (stop > p2_start):
        t = -t
    edges1 = _field_edge(scene, p1, float(pt.z[2]))
    tracer = _Curve(sys_, stop, step, edges1, p2_start)
    coef = _normal_form(sys_, pt)
    tracer.record(pt, coef)
    tracer.run(pt, t, coef)
    return tracer.curve(scene, point.kind, (p1, p2), k, int(point.winding))
