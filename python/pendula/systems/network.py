"""Networks of pendula: phases coupled by springs (inductances).

N phases φ_i obey

    C_i φ_i'' + β_i φ_i' + ε_i sin φ_i
        = τ_i + A_i cos(Ω_i t + ψ_i) + Σ_j K_ij (φ_j − φ_i − δ_ij) + noise,

K symmetric and non-negative (the springs), δ antisymmetric (the offsets a
flux threading a loop gives).  Two coupled pendula, a chain of pendula (the
Frenkel-Kontorova model, the discrete sine-Gordon equation), arrays of
Josephson junctions.  The kernel stores the couplings as a list of edges, so
a chain of 10⁴ costs O(N) a step (``kernel/models/pendula_network.f90``),
and integrates on the n-dimensional core (``kernel/integrators/pendula_ode.f90``):
DOP853 with dense output, Gauss-Legendre (symplectic) and BAOAB for noise.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from .. import _checks, _interrupt, _kernel
from .._optional import require
from .contract import STEPS_PER_PERIOD, NetworkTimeScales, network_rates, require_fields

if TYPE_CHECKING:   # xarray is optional: named in annotations only
    import xarray

__all__ = ["Network", "NetworkEquilibrium", "NormalModes", "TOPOLOGIES", "METHODS", "beat_period",
           "network_time_scales"]

#: the named topologies of :class:`Network`
TOPOLOGIES = ("pair", "chain", "ring", "ladder")
#: the integrators of :meth:`Network.simulate`
METHODS = ("dop853", "gauss6", "gauss4", "baoab")
_METHOD_CODE = {"dop853": 1, "gauss4": 2, "gauss6": 3}
_STATUS = {1: "the step dt must be positive and finite", 2: "rtol must be > 0 and atol >= 0",
           3: "unknown method", 5: "step size underflow (the problem may be singular or the "
                                   "tolerance unreachable)",
           6: "the state became non-finite",
           7: "the run needs more steps than the work limit (1e8 adaptive, 2e9 fixed-step): "
              "shorten the span, or give a larger dt or rtol",
           8: "interrupted", 20: "t must be ascending and >= 0",
           21: "an element with noise has no damping"}
_FIELDS = ("mass", "damping", "eps", "bias", "drive_amplitude", "drive_frequency", "drive_phase")


def _per_element(x, name: str, n: int, lo: float | None = None, lo_open: bool = False) -> np.ndarray:
    if type(x) is float and math.isfinite(x) and (lo is None or x > lo or (x == lo and not lo_open)):
        return np.full(n, x)    # one plain number in range: what the checks below would give, cheaply
    a = _checks.as_float(x, name)
    if a.ndim == 0:
        a = np.full(n, float(a))
    if a.shape != (n,):
        raise ValueError(f"{name} must be one number or {n} numbers (one per element), got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite")
    if lo is not None:
        bad = np.flatnonzero(a <= lo if lo_open else a < lo)
        if bad.size:
            rel = ">" if lo_open else ">="
            raise ValueError(f"{name} must be {rel} {lo:g}: element {bad[0]} is {a[bad[0]]!r}")
    return a


_FIELDS_ALLOWED: set = set()     # the field sets the capability table allowed for Network.simulate


def _require_simulate_fields(on: list) -> None:
    """The capability table's check of Network.simulate's fields, remembered when it passes."""
    key = tuple(on)
    if key not in _FIELDS_ALLOWED:
        require_fields("network", "simulate", on)
        _FIELDS_ALLOWED.add(key)


def _dataset(xr, data: dict, coords: dict, attrs: dict, made: dict | None = None):
    """xarray.Dataset(data, coords, attrs) for data of (dims, array) and 1-D coords named for their
    dimensions, built directly from its variables when this xarray allows (a fifth of the cost of the
    public constructor, whose alignment and merging are needless here), else by the constructor.  made:
    indexes built before (xarray PandasIndex, immutable) for some of the coords, shared, not rebuilt."""
    build = getattr(xr.Dataset, "_construct_direct", None)
    if build is not None:
        try:
            from xarray.core.indexes import PandasIndex
            import pandas as pd
            variables = {k: xr.Variable(d, a) for k, (d, a) in data.items()}
            made = made or {}
            indexes = {k: made[k] if k in made else PandasIndex(pd.Index(a, copy=False), k)
                       for k, a in coords.items()}
            for index in indexes.values():
                variables.update(index.create_variables())
            return build(variables=variables, coord_names=set(coords),
                         dims={k: len(a) for k, a in coords.items()}, indexes=indexes, attrs=attrs)
        except (ImportError, TypeError):   # another xarray's internals: the public way below
            pass
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _topology(name: str, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The springs (i < j, 0-based) of a named topology: a list, never an N x N matrix (a chain of 10⁴)."""
    if name == "pair":
        if n != 2:
            raise ValueError(f"topology 'pair' has 2 elements, got n={n}")
        return np.array([0]), np.array([1])
    if name in ("chain", "ring"):
        i = np.arange(n - 1)
        ei, ej = i, i + 1
        if name == "ring":
            if n < 3:
                raise ValueError(f"topology 'ring' needs n >= 3, got n={n}")
            ei, ej = np.append(ei, 0), np.append(ej, n - 1)
        return ei, ej
    # ladder: two rails of n/2 joined by rungs
    if n < 4 or n % 2:
        raise ValueError(f"topology 'ladder' needs an even n >= 4 (two rails), got n={n}")
    m = n // 2
    i, r = np.arange(m - 1), np.arange(m)
    return np.concatenate([i, m + i, r]), np.concatenate([i + 1, m + i + 1, m + r])


@dataclass(frozen=True)
class NetworkEquilibrium:
    """A rest point of an undriven network and its linear stability.

    Attributes
    ----------
    phi : numpy.ndarray
        The phases of the rest point (rad), one per element.
    energy : float
        Its potential energy (the network's energy at rest).
    eigenvalues : numpy.ndarray
        The 2N eigenvalues of the linearisation (complex), largest real part first.
    stable : bool
        True when the rest point is a strict minimum of the potential energy
        (its Hessian positive definite): the energy, which damping only
        removes, keeps the motion near it.
    residual : float
        The largest force left on an element (how well Newton converged).

    See Also
    --------
    Network.equilibrium : makes them.

    Examples
    --------
    >>> import pendula
    >>> net = pendula.Network(3, topology="chain", strength=1.0, bias=0.1)
    >>> eq = net.equilibrium([0, 0, 0])
    >>> eq.stable, round(float(eq.phi[0]), 12)
    (True, 0.100167421162)
    """

    phi: np.ndarray
    energy: float
    eigenvalues: np.ndarray
    stable: bool
    residual: float

    def __repr__(self) -> str:
        lo, hi = (float(np.min(self.phi)), float(np.max(self.phi))) if self.phi.size else (math.nan, math.nan)
        return (f"NetworkEquilibrium({self.phi.size} phases in [{lo:.6g}, {hi:.6g}], energy {self.energy:.10g}, "
                f"stable={self.stable}, residual {self.residual:.2g}, {self.eigenvalues.size} eigenvalues)")


@dataclass(frozen=True)
class NormalModes:
    """The normal modes of a network linearised about a rest point.

    Attributes
    ----------
    omega2 : numpy.ndarray
        The squared angular frequencies ω² (ascending): the eigenvalues of
        −C⁻¹J, J the force's Jacobian.  Negative for an unstable direction.
    shapes : numpy.ndarray
        The mode shapes, column k for omega2[k], normalised so that
        shapesᵀ C shapes = 1 (C the diagonal of masses).

    See Also
    --------
    Network.normal_modes : makes them.

    Examples
    --------
    >>> import pendula
    >>> modes = pendula.Network(2, topology="pair", strength=0.5).normal_modes()
    >>> [round(float(w), 12) for w in modes.frequencies]
    [1.0, 1.414213562373]
    """

    omega2: np.ndarray
    shapes: np.ndarray

    def __repr__(self) -> str:
        w2 = self.omega2
        span = f"omega2 from {float(w2[0]):.10g} to {float(w2[-1]):.10g}" if w2.size else "no modes"
        return f"NormalModes({w2.size} modes, {span}, {int(np.sum(w2 < 0))} unstable)"

    @property
    def frequencies(self) -> np.ndarray:
        """√ω² (rad per unit time); NaN, with a RuntimeWarning, for an unstable mode (ω² < 0)."""
        w2 = self.omega2
        if np.any(w2 < 0):
            warnings.warn("an unstable mode (omega2 < 0) has no real frequency: NaN", RuntimeWarning,
                          stacklevel=2)
        return np.sqrt(np.where(w2 >= 0, w2, np.nan))


class Network:
    """A network of N pendula (phases) coupled by springs.

    Parameters
    ----------
    n : int
        The number of elements, N >= 1 (N = 0 is refused).
    eps : float or array_like, optional
        ε_i, the strength of each element's sine force (default 1).
    damping : float or array_like, optional
        β_i >= 0 (default 0).
    mass : float or array_like, optional
        C_i > 0, each element's inertia (a junction's capacitance; default 1).
    bias : float or array_like, optional
        τ_i, a constant torque (bias current) on each element (default 0).
    drive_amplitude, drive_frequency, drive_phase : float or array_like, optional
        A_i, Ω_i, ψ_i of the drive A_i cos(Ω_i t + ψ_i) (default 0).
    coupling : array_like, optional
        The N x N matrix K of spring constants: symmetric, >= 0, zero
        diagonal.  Give either ``coupling`` or ``topology``.
    topology : {'pair', 'chain', 'ring', 'ladder'}, optional
        A named topology with every spring of stiffness ``strength``: two
        coupled pendula, an open chain, a ring, a ladder (two rails of N/2
        joined by rungs).
    strength : float, optional
        The spring constant of the named topology (>= 0; default 1).
    offset : array_like, optional
        The N x N antisymmetric matrix δ of the springs' rest offsets
        (default 0): spring i-j is relaxed at φ_j − φ_i = δ_ij.  Entries
        where there is no spring have no effect.

    Attributes
    ----------
    springs : tuple of numpy.ndarray
        The springs as the kernel stores them: their ends i < j (0-based),
        stiffness and offset.  A named topology is built as this list, so a
        chain of 10⁴ never forms an N x N matrix; ``coupling`` and
        ``offset`` give the dense matrices on request.

    Raises
    ------
    ValueError
        Naming the field: N = 0, a coupling not symmetric or of the wrong
        shape, a negative spring, a mass <= 0, a negative damping, an offset
        not antisymmetric.

    See Also
    --------
    Network.simulate, Network.equilibrium, Network.normal_modes, Network.energy

    Examples
    --------
    >>> import numpy as np, pendula
    >>> net = pendula.Network(2, topology="pair", strength=0.1)
    >>> run = net.simulate(np.linspace(0, 10, 3), phi0=[0.1, 0.0])
    >>> run.phi.dims, run.phi.shape
    (('time', 'element'), (3, 2))
    """

    def __init__(self, n: int, *, eps: ArrayLike = 1.0, damping: ArrayLike = 0.0, mass: ArrayLike = 1.0,
                 bias: ArrayLike = 0.0, drive_amplitude: ArrayLike = 0.0, drive_frequency: ArrayLike = 0.0,
                 drive_phase: ArrayLike = 0.0, coupling: ArrayLike | None = None, topology: str | None = None,
                 strength: float = 1.0, offset: ArrayLike | None = None) -> None:
        n = _checks.count(n, "n", 1, 10**8)
        self.n = n
        self.mass = _per_element(mass, "mass", n, 0.0, lo_open=True)
        self.damping = _per_element(damping, "damping", n, 0.0)
        self.eps = _per_element(eps, "eps", n)
        self.bias = _per_element(bias, "bias", n)
        self.drive_amplitude = _per_element(drive_amplitude, "drive_amplitude", n)
        self.drive_frequency = _per_element(drive_frequency, "drive_frequency", n)
        self.drive_phase = _per_element(drive_phase, "drive_phase", n)
        if (coupling is None) == (topology is None):
            raise ValueError("give exactly one of coupling (a matrix) and topology (a name)")
        if topology is not None:
            topology = _checks.choice(topology, "topology", TOPOLOGIES)
            ei, ej = _topology(topology, n)
            ek = np.full(ei.size, _checks.real(strength, "strength", 0.0))
        else:
            k = _checks.as_float(coupling, "coupling")
            if k.shape != (n, n):
                raise ValueError(f"coupling must be an {n} x {n} matrix (n={n}), got shape {k.shape}")
            if not np.all(np.isfinite(k)):
                raise ValueError("coupling must be finite")
            if not np.array_equal(k, k.T):
                i, j = np.argwhere(k != k.T)[0]
                raise ValueError(f"coupling must be symmetric: K[{i},{j}] = {k[i, j]!r} but "
                                 f"K[{j},{i}] = {k[j, i]!r}")
            if np.any(np.diag(k) != 0):
                raise ValueError("coupling must have a zero diagonal (an element is not coupled to itself)")
            if np.any(k < 0):
                i, j = np.argwhere(k < 0)[0]
                raise ValueError(f"coupling must be >= 0 (a spring, an inductance): K[{i},{j}] = {k[i, j]!r}")
            ei, ej = np.nonzero(np.triu(k, 1))
            ek = k[ei, ej]
        self.topology = topology
        if offset is None:
            eoff = np.zeros(ei.size)
        else:
            d = _checks.as_float(offset, "offset")
            if d.shape != (n, n):
                raise ValueError(f"offset must be an {n} x {n} matrix (n={n}), got shape {d.shape}")
            if not np.all(np.isfinite(d)):
                raise ValueError("offset must be finite")
            if not np.array_equal(d, -d.T):
                raise ValueError("offset must be antisymmetric (offset[j, i] = -offset[i, j])")
            eoff = d[ei, ej]
        #: the springs as a list: 0-based ends i < j, stiffness, offset (what the kernel stores)
        self.springs = (ei.astype(np.int64), ej.astype(np.int64), np.array(ek, dtype=np.float64),
                        np.array(eoff, dtype=np.float64))
        if ei.size == 0:   # no springs: one of stiffness 0 (it adds exact zeros), as f2py takes no empty arrays
            ei, ej, ek, eoff = np.array([0]), np.array([min(1, n - 1)]), np.zeros(1), np.zeros(1)
        self._ei = (ei + 1).astype(np.int32)
        self._ej = (ej + 1).astype(np.int32)
        self._ek = np.ascontiguousarray(ek, dtype=np.float64)
        self._eoff = np.ascontiguousarray(eoff, dtype=np.float64)
        self._p = np.asfortranarray(np.stack([self.mass, self.damping, self.eps, self.bias,
                                              self.drive_amplitude, self.drive_frequency, self.drive_phase]))
        self._on = [f for f in ("damping", "bias", "drive_amplitude") if np.any(getattr(self, f))]
        self._element_made: dict | None = None   # the element coordinate's index, built at the first result

    def __repr__(self) -> str:
        what = f"topology={self.topology!r}" if self.topology else f"{self.springs[0].size} springs"
        return f"Network(n={self.n}, {what})"

    def _fields_on(self) -> list:
        """The fields that are on (non-zero): the capability table decides what each tool does with them."""
        return list(self._on)

    @property
    def coupling(self) -> np.ndarray:
        """The spring constants K as a dense N x N matrix (built on request: for a small network)."""
        ei, ej, ek, _ = self.springs
        k = np.zeros((self.n, self.n))
        k[ei, ej] = ek
        return k + k.T

    @property
    def offset(self) -> np.ndarray:
        """The springs' offsets δ as a dense antisymmetric N x N matrix (built on request)."""
        ei, ej, _, eoff = self.springs
        d = np.zeros((self.n, self.n))
        d[ei, ej] = eoff
        return d - d.T

    def _edges(self):
        return self._p, self._ei, self._ej, self._ek, self._eoff

    def _state(self, x, name: str) -> np.ndarray:
        return _per_element(x, name, self.n)

    # ------------------------------------------------------------------ the force law
    def force(self, phi: ArrayLike, t: float = 0.0) -> np.ndarray:
        """The force on each element: everything but inertia and damping.

        Parameters
        ----------
        phi : array_like
            The phases, N numbers (or M x N for M sets at once).
        t : float, optional
            The time of the drive (default 0).

        Returns
        -------
        numpy.ndarray
            τ_i + A_i cos(Ω_i t + ψ_i) − ε_i sin φ_i + Σ_j K_ij (φ_j − φ_i − δ_ij), shaped as phi.

        Examples
        --------
        >>> import pendula
        >>> pendula.Network(2, topology="pair", strength=2.0).force([0.0, 0.5])
        array([ 1.        , -1.47942554])
        """
        q = _checks.as_float(phi, "phi")
        shape = q.shape
        q2 = np.asfortranarray(q.reshape(-1, self.n).T) if q.ndim > 0 and q.shape[-1] == self.n else None
        if q2 is None:
            raise ValueError(f"phi must hold {self.n} phases (the last axis), got shape {shape}")
        f, _ = _kernel.network_force_v(*self._edges(), _checks.real(t, "t"), q2)
        return f.T.reshape(shape)

    def jacobian(self, phi: ArrayLike) -> np.ndarray:
        """The Jacobian of :meth:`force` in the phases, N x N (symmetric).

        Parameters
        ----------
        phi : array_like
            The phases, N numbers.

        Returns
        -------
        numpy.ndarray
            J_ij = ∂f_i/∂φ_j.

        Examples
        --------
        >>> import pendula
        >>> pendula.Network(2, topology="pair", strength=2.0).jacobian([0, 0])
        array([[-3.,  2.],
               [ 2., -3.]])
        """
        q = np.asfortranarray(self._state(phi, "phi").reshape(self.n, 1))
        _, jac = _kernel.network_force_v(*self._edges(), 0.0, q)
        return jac

    def energy(self, phi: ArrayLike, v: ArrayLike) -> np.ndarray:
        """The energy Σ C_i v_i²/2 + Σ [ε_i (1 − cos φ_i) − τ_i φ_i] + Σ_{i<j} K_ij (φ_j − φ_i − δ_ij)²/2.

        Conserved when there is no damping, drive or noise.

        Parameters
        ----------
        phi, v : array_like
            Phases and velocities, N numbers or M x N (M states).

        Returns
        -------
        float or numpy.ndarray
            The energy of each state.

        Examples
        --------
        >>> import math, pendula
        >>> net = pendula.Network(2, topology="pair", strength=1.0)
        >>> float(net.energy([0.0, math.pi], [0.0, 0.0]))
        6.934802200544679
        """
        q = _checks.as_float(phi, "phi")
        w = _checks.as_float(v, "v")
        if q.shape != w.shape or q.ndim == 0 or q.shape[-1] != self.n:
            raise ValueError(f"phi and v must have the same shape with {self.n} elements last, "
                             f"got {q.shape} and {w.shape}")
        y = np.asfortranarray(np.concatenate([q.reshape(-1, self.n), w.reshape(-1, self.n)], axis=1).T)
        en = _kernel.network_energy_v(*self._edges(), y)
        return en.reshape(q.shape[:-1]) if q.ndim > 1 else float(en[0])

    # ------------------------------------------------------------------ time evolution
    def time_scales(self, v0: ArrayLike = 0.0) -> NetworkTimeScales:
        """The network's time scales and its methods' default steps (the kernel's one rule).

        Parameters
        ----------
        v0 : float or array_like, optional
            The elements' starting speeds (default 0).

        Returns
        -------
        NetworkTimeScales

        See Also
        --------
        pendula.network_time_scales : the same, as a function.

        Examples
        --------
        >>> import pendula
        >>> pendula.Network(2, topology="pair", strength=4.0, damping=0.5).time_scales().fastest
        3.0
        """
        return network_time_scales(self, v0)

    def simulate(self, t: ArrayLike, phi0: ArrayLike = 0.0, v0: ArrayLike = 0.0, *, method: str = "dop853",
                 rtol: float = 1e-10, atol: float = 1e-12, dt: float | None = None, temperature: ArrayLike = 0.0,
                 seed: int = 0, paths: int = 1, first_path: int = 0, threads: int = 0) -> xarray.Dataset:
        """The motion of the network at the times t, as an xarray Dataset.

        Parameters
        ----------
        t : array_like
            Output times, ascending, >= 0 (the run starts at t = 0).  For the
            fixed-step methods they must lie on the step grid (multiples of dt).
        phi0, v0 : float or array_like, optional
            The initial phases and velocities (one number for all, or N).
            A batch of B initial states: phi0 of shape (B, N) (v0 one number,
            N, or B x N); the B runs go in one kernel call on OpenMP threads,
            each run's result the same as its own call's, on any thread count.
        method : {'dop853', 'gauss6', 'gauss4', 'baoab'}, optional
            DOP853 with dense output (adaptive: rtol, atol); Gauss-Legendre of
            order 6 or 4 (fixed step dt; symplectic: the energy of a
            conservative network stays bounded); BAOAB, the Langevin
            integrator of thermal noise (fixed step dt; chosen whenever a
            temperature is given).
        rtol, atol : float, optional
            DOP853's tolerances (default 1e-10, 1e-12).
        dt : float, optional
            The step of the fixed-step methods.  Default: from the network's
            fastest time scale (:meth:`time_scales`: 2 pi over the fastest rate
            over 100 steps), shortened to
            divide the spacing of the times, which must then lie on a grid of
            equal steps from 0.
        temperature : float or array_like, optional
            T_i >= 0 of each element, in the energy units of ε and K: noise of
            strength √(2 β_i T_i) (fluctuation-dissipation), so that each
            element's ⟨C_i v_i²⟩ = T_i.  An element with T_i > 0 needs damping.
        seed : int, optional
            The seed of the noise (>= 0).  Element i of path k draws from the
            stream keyed by (seed, first_path + k, i): the same numbers on any
            thread count.
        paths : int, optional
            The number of noisy paths (default 1), run on OpenMP threads.
        first_path : int, optional
            The index of the first path's stream (to continue a set of paths).
        threads : int, optional
            OpenMP threads for the paths or the batch (0: OpenMP's default).

        Returns
        -------
        xarray.Dataset
            ``phi`` and ``v`` over (``time``, ``element``) (with ``path`` first
            for BAOAB, ``run`` first for a batch), ``energy`` over ``time``
            (and ``path`` or ``run``); attributes ``method``, ``dt`` for the
            fixed-step methods and, for the deterministic methods, ``steps``
            and ``rhs_evaluations`` (of each run, an array, for a batch).

        Raises
        ------
        ValueError
            Naming the field (times not ascending or off the step grid, no
            dt given for times off every grid of equal steps, noise on an
            undamped element), or the kernel's failure
            (a state that left the doubles, the work limit).

        Examples
        --------
        >>> import numpy as np, pendula
        >>> net = pendula.Network(4, topology="chain", damping=1.0)
        >>> run = net.simulate(np.arange(0, 5.0, 1.0), dt=0.05, temperature=0.1,
        ...                    paths=2, seed=3)
        >>> run.phi.dims, run.attrs["method"]
        (('path', 'time', 'element'), 'baoab')
        >>> net.simulate([0.0, 1.0], np.zeros((3, 4)), 0.1).phi.dims   # a batch of 3 initial states
        ('run', 'time', 'element')
        """
        xr = require("xarray", "xarray", "Network.simulate")
        tt = _checks.as_float(t, "t").ravel()
        method = _checks.choice(method, "method", METHODS)
        temp = _per_element(temperature, "temperature", self.n, 0.0)
        noisy = bool(np.any(temp > 0))
        _require_simulate_fields(self._on + (["temperature"] if noisy else []))
        if noisy:
            method = "baoab"
            bad = np.flatnonzero((temp > 0) & (self.damping == 0))
            if bad.size:
                raise ValueError(f"temperature: element {bad[0]} has no damping, and noise without "
                                 "damping has no equilibrium (fluctuation-dissipation); give it damping > 0")
        y0, batch = self._initial_states(phi0, v0)
        counts = None
        # the starting speeds the time scales see: of each element, the largest over a batch's runs
        scales = self.time_scales(np.abs(y0[self.n:]).max(axis=1) if batch else y0[self.n:])
        if method != "dop853":
            if tt.size and not (np.all(np.diff(tt) >= 0) and tt[0] >= 0):
                raise ValueError("t must be ascending and >= 0")
            h = _grid_step(tt, scales.default_dt[method]) if dt is None else _checks.real(dt, "dt", 0.0, lo_open=True)
            steps = tt / h
            if steps.size and not steps[-1] <= 2e9:   # the kernel's fixed-step work limit (max_fixed_steps)
                raise ValueError(f"t, dt: {_STATUS[7]}")
            counts = np.rint(steps)
            if np.any(np.abs(steps - counts) > 1e-9 * np.maximum(1.0, steps)):
                raise ValueError(f"t must lie on the step grid of dt={h!r} (multiples of dt)")
            counts = np.diff(np.concatenate([[0.0], counts])).astype(np.int64)
        cancel = _interrupt.cancel_flag()
        span = float(tt[-1]) if tt.size else 0.0
        npath = _checks.count(paths, "paths", 1) if method == "baoab" else 1
        if batch and method == "baoab":
            if npath not in (1, y0.shape[1]):
                raise ValueError(f"paths: {npath} paths but {y0.shape[1]} initial states (phi0's rows)")
            npath = y0.shape[1]
        nrun = y0.shape[1] if batch else 1
        if method == "dop853":
            # a rough count of element-evaluations (12 per step) from the fastest time scale: short runs skip
            # the interruptible thread's start
            long = self.n * nrun * span * scales.fastest / (2 * math.pi) * STEPS_PER_PERIOD * 12 > 1e6
        else:
            long = self.n * span / h * (npath if method == "baoab" else 10 * nrun) > 1e6
        if method == "baoab":
            seed = _checks.count(seed, "seed", 0, 2**63 - 1)
            first = _checks.count(first_path, "first_path", 0, 2**63 - 1)
            y0s = y0 if batch else np.asfortranarray(np.repeat(y0[:, None], npath, axis=1))
            yout, status = _interrupt.call(_kernel.network_langevin_v, *self._edges(), temp, seed, first, h,
                                           y0s, counts, _checks.threads(threads), cancel, cancel=cancel,
                                           long=long)
            bad = status[status != 0]
            if bad.size:
                raise ValueError(f"baoab: {_STATUS.get(int(bad[0]), f'kernel status {bad[0]}')}")
            phi = np.transpose(yout[:self.n], (2, 1, 0))
            v = np.transpose(yout[self.n:], (2, 1, 0))
            en = self.energy(phi, v)
            dims = ("path", "time", "element")
            return _dataset(xr, {"phi": (dims, phi), "v": (dims, v), "energy": (dims[:2], en)},
                            {"path": np.arange(first, first + npath), "time": tt, "element": np.arange(self.n)},
                            {"method": "baoab", "seed": seed, "dt": h})
        if method == "dop853":
            rtol, atol = _checks.tolerances(rtol, atol)
            counts = np.zeros(tt.size, dtype=np.int64)
            h = 0.0
        if batch:
            return self._simulate_batch(xr, method, y0, tt, counts, rtol, atol, h, threads, cancel, long)
        yout, stats, status = _interrupt.call(
            _kernel.network_simulate_v, *self._edges(), _METHOD_CODE[method], y0, tt, counts,
            float(rtol), float(atol), h, cancel, cancel=cancel, long=long)
        if status != 0:
            raise ValueError(f"{method}: {_STATUS.get(int(status), f'kernel status {status}')}")
        phi, v = yout[:self.n].T, yout[self.n:].T
        dims = ("time", "element")
        en = _kernel.network_energy_v(*self._edges(), yout)
        return _dataset(xr, {"phi": (dims, phi), "v": (dims, v), "energy": (("time",), en)},
                        {"time": tt, "element": np.arange(self.n)},
                        {"method": method, "steps": int(stats[0]), "rhs_evaluations": int(stats[3]),
                         **({"dt": h} if method != "dop853" else {})},
                        self._element_index())

    def _element_index(self) -> dict:
        """The element coordinate's xarray index, built once (every result of this network shares it)."""
        made = self._element_made
        if made is None:
            try:
                from xarray.core.indexes import PandasIndex
                import pandas as pd
                made = {"element": PandasIndex(pd.Index(np.arange(self.n)), "element")}
            except ImportError:     # another xarray's internals: built each time by _dataset
                made = {}
            self._element_made = made
        return made

    def _initial_states(self, phi0, v0) -> tuple[np.ndarray, bool]:
        """The initial state y0 = (phi0, v0), or for phi0 of B rows the 2N x B states (Fortran order)."""
        q = phi0 if type(phi0) is float else _checks.as_float(phi0, "phi0")
        if np.ndim(q) < 2:
            return np.concatenate([self._state(q, "phi0"), self._state(v0, "v0")]), False
        if q.ndim != 2 or q.shape[1] != self.n or q.shape[0] == 0:
            raise ValueError(f"phi0 must be one number, {self.n} numbers, or B x {self.n} (a batch), "
                             f"got shape {q.shape}")
        w = _checks.as_float(v0, "v0")
        if w.shape not in ((), (self.n,), q.shape):
            raise ValueError(f"v0 must be one number, {self.n} numbers or {q.shape[0]} x {self.n} "
                             f"(one row per initial state), got shape {w.shape}")
        for name, a in (("phi0", q), ("v0", w)):
            if not np.all(np.isfinite(a)):
                raise ValueError(f"{name} must be finite")
        return np.asfortranarray(np.concatenate([q, np.broadcast_to(w, q.shape)], axis=1).T), True

    def _simulate_batch(self, xr, method, y0, tt, counts, rtol, atol, h, threads, cancel, long):
        """simulate's deterministic runs from the columns of y0, in one kernel call."""
        yout, stats, status = _interrupt.call(
            _kernel.network_simulate_batch_v, *self._edges(), _METHOD_CODE[method], y0, tt, counts,
            float(rtol), float(atol), h, _checks.threads(threads), cancel, cancel=cancel, long=long)
        bad = np.flatnonzero(status != 0)
        if bad.size:
            code = int(status[bad[0]])
            raise ValueError(f"{method}: run {bad[0]}: {_STATUS.get(code, f'kernel status {code}')}")
        nout, nrun = tt.size, y0.shape[1]
        en = _kernel.network_energy_v(*self._edges(), yout.reshape(2 * self.n, nout * nrun, order="F"))
        dims = ("run", "time", "element")
        return _dataset(xr, {"phi": (dims, np.transpose(yout[:self.n], (2, 1, 0))),
                             "v": (dims, np.transpose(yout[self.n:], (2, 1, 0))),
                             "energy": (dims[:2], en.reshape((nout, nrun), order="F").T)},
                        {"run": np.arange(nrun), "time": tt, "element": np.arange(self.n)},
                        {"method": method, "steps": stats[0].copy(), "rhs_evaluations": stats[3].copy(),
                         **({"dt": h} if method != "dop853" else {})},
                        self._element_index())

    # ------------------------------------------------------------------ rest points and modes
    def equilibrium(self, phi: ArrayLike, *, tol: float = 1e-14, maxit: int = 50) -> NetworkEquilibrium:
        """The rest point Newton's method reaches from the phases phi.

        Parameters
        ----------
        phi : float or array_like
            The starting phases (one number for all, or N).
        tol : float, optional
            Newton stops when a step moves no phase by more than
            tol (1 + abs(φ)) (default 1e-14).  Steps longer than 1 rad are
            shortened to 1 rad (a start far from a rest point).
        maxit : int, optional
            The most Newton steps (default 50).

        Returns
        -------
        NetworkEquilibrium

        Raises
        ------
        ValueError
            When the network is driven (a driven network has no rest points)
            or Newton does not converge (the message says how close it got).

        Examples
        --------
        >>> import numpy as np, pendula
        >>> net = pendula.Network(2, topology="pair", strength=0.3)
        >>> eq = net.equilibrium([3.0, 3.1])
        >>> np.round(eq.phi, 12).tolist(), eq.stable
        ([3.14159265359, 3.14159265359], False)
        """
        require_fields("network", "equilibrium", self._fields_on())
        tol = _checks.real(tol, "tol", 0.0, lo_open=True)
        maxit = _checks.count(maxit, "maxit", 1)
        q = self._state(phi, "phi").copy()
        prev = math.inf
        for _ in range(maxit):
            f = self.force(q)
            jac = self.jacobian(q)
            try:
                d = np.linalg.solve(jac, -f)
            except np.linalg.LinAlgError:
                raise ValueError("phi: Newton met a singular Jacobian (a fold of the rest points); "
                                 "start elsewhere") from None
            big = float(np.max(np.abs(d)))
            if big > 1.0:   # far from a rest point: no phase moves more than 1 rad a step
                d = d / big
            q = q + d
            if np.all(np.abs(d) <= tol * (1.0 + np.abs(q))):
                break
            # at the rounding level the steps stop shrinking: converged as far as the force can say
            scale = float(np.max(1.0 + np.abs(q)))
            if big <= 1e-10 * scale and big >= 0.5 * prev:
                break
            prev = big
        else:
            raise ValueError(f"phi: Newton did not converge in {maxit} steps "
                             f"(last step {np.max(np.abs(d)):.3g})")
        res = float(np.max(np.abs(self.force(q))))
        jac = self.jacobian(q)
        a = np.zeros((2 * self.n, 2 * self.n))
        a[:self.n, self.n:] = np.eye(self.n)
        a[self.n:, :self.n] = jac / self.mass[:, None]
        a[self.n:, self.n:] = -np.diag(self.damping / self.mass)
        lam = np.linalg.eigvals(a)
        lam = lam[np.lexsort((-lam.imag, -lam.real))]
        # the energy is a Lyapunov function (damping >= 0 only removes it): a strict minimum of the
        # potential is stable, a direction of descent unstable; the eigenvalues' real parts of an undamped
        # network are zero only up to rounding, so the Hessian decides
        stable = bool(np.all(np.linalg.eigvalsh(-jac) > 0))
        en = self.energy(q, np.zeros(self.n))
        return NetworkEquilibrium(q, float(en), lam, stable, res)

    def normal_modes(self, phi: ArrayLike | None = None) -> NormalModes:
        """The normal modes of the undamped network linearised about a rest point.

        Parameters
        ----------
        phi : array_like, optional
            The rest point (default: the one :meth:`equilibrium` reaches
            from all phases 0).

        Returns
        -------
        NormalModes
            ω² ascending and the mode shapes: −J x = ω² C x.

        Raises
        ------
        ValueError
            Naming the field, for a damped or driven network (the capability
            table: its modes are the undamped, undriven network's; a damped
            network's rates are :meth:`equilibrium`'s eigenvalues).

        Examples
        --------
        >>> import numpy as np, pendula
        >>> modes = pendula.Network(3, topology="ring", strength=1.0).normal_modes()
        >>> np.round(modes.omega2, 12).tolist()
        [1.0, 4.0, 4.0]
        """
        require_fields("network", "normal_modes", self._fields_on())
        q = self.equilibrium(np.zeros(self.n)).phi if phi is None else self._state(phi, "phi")
        jac = self.jacobian(q)
        s = 1.0 / np.sqrt(self.mass)
        w2, u = np.linalg.eigh(-(s[:, None] * jac * s[None, :]))
        return NormalModes(w2, s[:, None] * u)


def network_time_scales(network: Network, v0: ArrayLike = 0.0) -> NetworkTimeScales:
    """The time scales of a network of pendula, from the kernel's one time-scale rule.

    Parameters
    ----------
    network : Network
        Any :class:`~pendula.Network`.
    v0 : float or array_like, optional
        The elements' starting speeds (one number or N; default 0): a fast
        rotation is a time scale too.

    Returns
    -------
    NetworkTimeScales
        The rates of every scale, the fastest, and the default steps of the
        fixed-step methods.

    See Also
    --------
    pendula.time_scales : the same rule for a scene.
    Network.time_scales : the same, as a method.

    Examples
    --------
    >>> import pendula
    >>> net = pendula.Network(3, topology="chain", strength=1e4)
    >>> ts = pendula.network_time_scales(net)
    >>> round(ts.fastest, 4), round(ts.default_dt["gauss6"], 9)
    (200.0025, 0.000314155)
    """
    p, ei, ej, ek, _ = network._edges()
    return network_rates(p, ei, ej, ek, network._state(v0, "v0"))


def _grid_step(t: np.ndarray, h0: float) -> float:
    """The largest step <= h0 that divides the spacing of the times t, which lie on a grid of equal steps from 0."""
    grid = np.unique(np.concatenate([[0.0], t]))
    if grid.size < 2:
        return h0
    base = float(np.min(np.diff(grid)))
    k = grid / base
    if np.any(np.abs(k - np.rint(k)) > 1e-9 * np.maximum(1.0, k)):
        raise ValueError("dt: the times t are not on a grid of equal steps from 0, so no default step "
                         "divides them; give dt")
    return base / math.ceil(base / h0)


def beat_period(strength: float, eps: float = 1.0, mass: float = 1.0) -> float:
    """The beat period of two equal coupled pendula at small amplitude: 2π / (ω₂ − ω₁).

    ω₁² = ε/C and ω₂² = (ε + 2K)/C, the in-phase and the opposite-phase modes.

    Parameters
    ----------
    strength : float
        The spring K > 0.
    eps, mass : float, optional
        ε and C of each pendulum (default 1).

    Returns
    -------
    float

    Examples
    --------
    >>> round(beat_period(0.05), 9)
    128.73045652
    """
    k = _checks.real(strength, "strength", 0.0, lo_open=True)
    e = _checks.real(eps, "eps", 0.0, lo_open=True)
    c = _checks.real(mass, "mass", 0.0, lo_open=True)
    w1, w2 = math.sqrt(e / c), math.sqrt((e + 2 * k) / c)
    return 2 * math.pi / (w2 - w1)
