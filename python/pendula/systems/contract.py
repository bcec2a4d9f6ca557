"""The system contract, read from the kernel: which tool honours which effect
on which system, the time scales a scene's fields create, and what counts as a
periodic forcing.

The rules live once, in the kernel (``kernel/dispatch/pendula_system.f90`` and
``kernel/models/pendula_time_scales.f90``); this module only asks.  Every tool
calls :func:`require` at its door, so a scene field a tool does not honour is
refused by name, never silently ignored.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

from .. import _kernel
from ..scene import Scene, SceneError

__all__ = ["Capability", "TimeScales", "NetworkTimeScales", "capabilities", "require", "require_fields", "time_scales", "forcing_frequency",
           "expected_steps", "EFFECTS", "STEPS_PER_PERIOD", "MAX_POINT_STEPS"]

#: the effects of the capability table, in its order, and the field that turns each on
EFFECTS = {"damping": "damping", "torque": "torque", "drive": "drive_amplitude", "friction": "friction",
           "drag": "drag", "pivot": "pivot_amplitude", "noise": "noise", "force": "force"}

_REFUSED, _NOT_IMPLEMENTED, _UNKNOWN_TOOL, _NOT_A_SCENE = 2, 3, 4, 100


@dataclass(frozen=True)
class Capability:
    """One row of the capability table: what one tool does on one system.

    Attributes
    ----------
    tool : str
        The tool ('simulate', 'periodic_orbit', 'sweep:mean_velocity', ...).
    system : str
        The system (model) it runs: 'rigid', 'cord', 'cycloid', 'gravity' (the
        models a Scene selects), or 'network', 'double', 'foucault', 'spherical'.
    honours : tuple of str
        The effects it honours: each changes its answer.
    planned : tuple of str
        The effects it will honour but does not yet (NotImplementedError).
    needs : tuple of str
        Effects of which at least one must be on (a periodic forcing: drive or pivot).
    note : str
        Why the other effects are refused.

    See Also
    --------
    capabilities : the whole table.

    Examples
    --------
    >>> import pendula
    >>> row = [c for c in pendula.capabilities()
    ...        if c.tool == "periodic_orbit" and c.system == "rigid"][0]
    >>> "noise" in row.honours, row.needs
    (False, ('drive', 'pivot'))
    """

    tool: str
    system: str
    honours: tuple
    planned: tuple
    needs: tuple
    note: str


@functools.cache
def capabilities() -> tuple[Capability, ...]:
    """The capability table: for every tool and system, the effects honoured.

    An effect a row does not list is refused by that tool with a message
    naming the scene field (a ``ValueError``), or, when planned, a
    ``NotImplementedError``; a tool with no row for a system does not run it.
    ``pendula models`` prints the same table.

    Returns
    -------
    tuple of Capability
        One row per (tool, system), in the kernel's order.

    See Also
    --------
    models : the systems and their exact paths.

    Examples
    --------
    >>> import pendula
    >>> tools = sorted({c.tool for c in pendula.capabilities()})
    >>> "simulate" in tools and "attractor_map" in tools
    True
    """
    text = _kernel.capability_table_v()
    text = text.decode() if isinstance(text, bytes) else str(text)
    rows = []
    for line in text.strip().splitlines():
        tool, system, honours, planned, needs, note = (f.strip() for f in line.split("|"))
        rows.append(Capability(tool, system, tuple(honours.split()), tuple(planned.split()), tuple(needs.split()),
                               note))
    return tuple(rows)


def require(scene: Scene, tool: str, over=(), force: bool = False) -> None:
    """Refuse, by the field's name, what ``tool`` does not honour in ``scene``.

    ``over``: the names of the fields a sweep varies (an effect swept from 0 is
    on); ``force``: a user's force is given.  Raises ValueError for a refused
    effect or a missing forcing, NotImplementedError for a system the tool does
    not run or an effect it does not honour yet.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a pendula.Scene, got {type(scene).__name__}")
    x, words, wlen, nout, ngrid = scene._kernel_fields
    swept = " ".join(str(k) for k in over)
    status, msg = _kernel.capability_check_v(x, words, wlen, nout, ngrid, tool.encode(), swept.encode() or b" ",
                                             int(bool(force)))
    if status == 0:
        return
    msg = (msg.decode(errors="replace") if isinstance(msg, bytes) else str(msg)).strip()
    if status == _NOT_IMPLEMENTED:
        raise NotImplementedError(msg)
    if status == _NOT_A_SCENE:
        raise SceneError(f"the kernel refused the scene: {msg}")
    if status == _UNKNOWN_TOOL:
        raise RuntimeError(msg)      # a tool of pendula's own that the table lacks: a bug, said plainly
    raise ValueError(msg)


def require_fields(system: str, tool: str, on) -> None:
    """Refuse, by the field's name, what ``tool`` does not honour in a system built by its own class.

    ``system``: the registry's name ('network', 'double', 'foucault', 'spherical'); ``on``: the names
    of the system's fields (or the tool's arguments) that are non-zero.  The kernel's registry says which
    effect each field turns on, its capability table which effects the tool honours.  Raises ValueError
    naming the field for a refused effect, NotImplementedError for a planned one.
    """
    fields = " ".join(str(k) for k in on)
    status, msg = _kernel.capability_check_fields_v(system.encode(), tool.encode(), fields.encode() or b" ")
    if status == 0:
        return
    msg = (msg.decode(errors="replace") if isinstance(msg, bytes) else str(msg)).strip()
    if status == _NOT_IMPLEMENTED:
        raise NotImplementedError(msg)
    if status == _UNKNOWN_TOOL:
        raise RuntimeError(msg)      # a system, tool or field of pendula's own that the table lacks: a bug
    raise ValueError(msg)


@dataclass(frozen=True)
class TimeScales:
    """The time scales a scene's fields create (the kernel's one rule).

    Attributes
    ----------
    rates : dict
        Each scale's rate (1 / time, 0 where the field is absent): 'oscillation'
        (sqrt of eps times the field's stiffness), 'damping' (beta), 'drive' and
        'pivot' (their angular frequencies), 'pivot_force' (sqrt(a) Omega_p),
        'torque' (sqrt(abs(tau))), 'friction', 'drag', 'rotation' (abs(v0)).
    fastest : float
        The fastest rate: it bounds every method's step.
    forcing_frequency : float
        The angular frequency of the scene's periodic forcing (drive or pivot), 0 when autonomous.
    langevin_dt : float
        The Langevin integrator's default step for this scene.

    See Also
    --------
    time_scales : computes them for a scene.

    Examples
    --------
    >>> import pendula
    >>> ts = pendula.time_scales(pendula.Scene(damping=100.0))
    >>> ts.rates["damping"], round(ts.langevin_dt, 6)
    (100.0, 0.000628)
    """

    rates: dict
    fastest: float
    forcing_frequency: float
    langevin_dt: float
    forcing_status: int

    def __repr__(self) -> str:
        on = ", ".join(f"{k} {v:.3g}" for k, v in self.rates.items() if v)
        return f"TimeScales(rates: {on or 'none'}; fastest {self.fastest:.3g}, forcing {self.forcing_frequency:.3g})"


def time_scales(scene: Scene) -> TimeScales:
    """The time scales of a scene, from the kernel's one time-scale rule.

    Parameters
    ----------
    scene : Scene
        Any scene.

    Returns
    -------
    TimeScales
        The rates of every scale, the fastest, the forcing frequency and the
        Langevin default step.

    Raises
    ------
    SceneError
        The kernel refuses the scene's fields (a scene made by ``Scene`` never is).

    See Also
    --------
    capabilities : which tool honours which effect.

    Examples
    --------
    >>> import pendula
    >>> s = pendula.Scene(pivot_amplitude=1e4, pivot_frequency=40.0)
    >>> pendula.time_scales(s).fastest
    4000.0
    """
    known = scene.__dict__.get("_time_scales")
    if known is not None:
        return known
    x, words, wlen, nout, ngrid = scene._kernel_fields
    rates, names, omega, fstatus, ldt, status = _kernel.scene_time_scales_v(x, words, wlen, nout, ngrid)
    if status:
        raise SceneError("the kernel refused the scene's fields")
    names = names.decode() if isinstance(names, bytes) else str(names)
    keys = [names[12 * i:12 * (i + 1)].strip() for i in range(len(rates))]
    r = {k: float(v) for k, v in zip(keys, rates)}
    ts = TimeScales(r, max(r.values()), float(omega), float(ldt), int(fstatus))
    object.__setattr__(scene, "_time_scales", ts)
    return ts


@dataclass(frozen=True)
class NetworkTimeScales:
    """The time scales of a network of pendula (the kernel's one rule for networks).

    Attributes
    ----------
    rates : dict
        Each scale's rate (1 / time, the fastest over the elements, 0 where the
        field is absent): 'oscillation' sqrt(abs(eps_i) / C_i), 'coupling'
        sqrt(2 k_i / C_i) with k_i the sum of element i's springs (Gershgorin's
        bound of the springs' fastest normal mode), 'modes' sqrt((abs(eps_i) +
        2 k_i) / C_i) (the bound of the linearised network's fastest mode),
        'damping' beta_i / C_i, 'drive' Omega_i, 'drive_force' sqrt(abs(A_i) / C_i),
        'torque' sqrt(abs(tau_i) / C_i), 'running' (abs(tau_i) + abs(A_i)) / beta_i
        (a damped element driven over the top), 'rotation' (the starting speed).
    fastest : float
        The fastest rate: it bounds every method's step.
    default_dt : dict
        The default step of each fixed-step method of :meth:`Network.simulate
        <pendula.Network.simulate>` ('gauss4', 'gauss6', 'baoab'): 2 pi over the
        fastest rate divided by the method's steps per period (100 each).

    See Also
    --------
    pendula.network_time_scales : computes them.

    Examples
    --------
    >>> import pendula
    >>> ts = pendula.Network(2, topology="pair", strength=4.0).time_scales()
    >>> ts.rates["coupling"], ts.fastest
    (2.8284271247461903, 3.0)
    """

    rates: dict
    fastest: float
    default_dt: dict

    def __repr__(self) -> str:
        on = ", ".join(f"{k} {v:.3g}" for k, v in self.rates.items() if v)
        steps = ", ".join(f"{k} {v:.3g}" for k, v in self.default_dt.items())
        return f"NetworkTimeScales(rates: {on or 'none'}; fastest {self.fastest:.3g}; default dt: {steps})"


def network_rates(p, ei, ej, ek, v0) -> NetworkTimeScales:
    """The time scales of a network from its kernel data (the parameter block, the springs 1-based and
    the starting speeds): the kernel's rule read, as :func:`pendula.network_time_scales` shows it."""
    rates, names, dts = _kernel.network_time_scales_v(p, ei, ej, ek, v0)
    names = names.decode() if isinstance(names, bytes) else str(names)
    keys = [names[12 * i:12 * (i + 1)].strip() for i in range(len(rates))]
    r = {k: float(x) for k, x in zip(keys, rates)}
    return NetworkTimeScales(r, max(r.values()), dict(zip(("gauss4", "gauss6", "baoab"), map(float, dts))))


#: the work a sweep point may be asked for before any work is done (expected integration steps: about
#: 10 s of one core); a longer window is refused, naming the field that makes it long
MAX_POINT_STEPS = 1e7

#: the adaptive steps one period of the fastest time scale takes at rtol 1e-10 (DOP853 and the Verner
#: pairs on the work-precision study's problems: 20-40)
STEPS_PER_PERIOD = 30.0


def expected_steps(scene: Scene, span: float, rtol: float | None = None) -> float:
    """The adaptive steps a span of the scene's motion is expected to take: the span in periods of its
    fastest time scale, times STEPS_PER_PERIOD scaled by the tolerance (an 8th-order method: rtol^(-1/8))."""
    rtol = scene.rtol if rtol is None else rtol
    per_period = STEPS_PER_PERIOD * max(1.0, 1e-10 / rtol) ** 0.125 if rtol > 0 else float("inf")
    return abs(span) * time_scales(scene).fastest / (2 * math.pi) * per_period


def forcing_frequency(scene: Scene, who: str = "this tool") -> float:
    """The angular frequency of a scene's periodic forcing (the kernel's one
    definition: a drive with amplitude and frequency, a vibrating pivot, or both
    at one frequency); ValueError naming the fields when there is none or two."""
    ts = time_scales(scene)
    if ts.forcing_status == 2:
        raise ValueError(f"fields 'drive_frequency' and 'pivot_frequency': {who} needs one forcing period; "
                         "give the drive and the pivot the same frequency")
    if ts.forcing_status == 1:
        raise ValueError(f"drive_amplitude, drive_frequency: {who} needs a periodically driven scene "
                         "(drive_amplitude and drive_frequency non-zero, or a vibrating pivot)")
    return ts.forcing_frequency
