"""Scenes: what to simulate, and nothing more.

A scene is a small text file holding one Fortran namelist group ``&scene``::

    &scene
      name = 'near the separatrix from below'
      eps = 1.0                 ! g / l  (or give g and length)
      theta0 = 0.0, v0 = 1.999
      t_end = 40.0, n_samples = 2001
      outputs = 'theta_t', 'phase'
      sweep = 'v0', sweep_values = 1.7, 1.8, 1.9, 1.95
    /

One reader and one rule book read and check every scene: the kernel's
(kernel/io/pendula_scene.f90).  :meth:`Scene.from_file` and
:meth:`Scene.from_namelist` hand it the text; ``Scene(...)`` and
:meth:`Scene.replace` hand it the fields; the batch executable ``pendula-run``
reads files with it.  So Python and ``pendula-run`` accept and refuse the same
scenes with the same message.  A scene names the effects it wants by giving
their parameters (``damping``, ``torque``, ``drive_amplitude`` ...); effects it
does not name are not in the model, and a conservative rigid pendulum is
answered by the exact solution.  A field that is unknown, misspelled, of the
wrong type or out of range, or an output the scene cannot have, is an error
that names it.
"""

from __future__ import annotations

import dataclasses
import difflib
import functools
import math
import os
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from . import _kernel

#: Trajectory columns and derived outputs a scene may ask for.
OUTPUTS = ("trajectory", "theta_t", "v_t", "phase", "energy", "period", "omega", "theta_max",
           "series", "lindstedt", "spectrum")
#: Methods: the exact path and the integrators.
METHODS = ("auto", "exact", "rk4", "verlet", "yoshida4", "yoshida6", "yoshida8", "gauss4", "gauss6",
           "dopri5", "dop853", "gsl-rk8pd", "dprkn6", "vern9", "vern8")
CORDS = ("rigid", "flexible")
GUIDES = ("none", "cycloid")
GRAVITIES = ("uniform", "inverse-square", "linear")
SWEEPABLE = ("v0", "theta0", "eps", "damping", "torque", "drive_amplitude", "drive_frequency")
#: what a sweep point can answer (see pendula.sweeps)
MEASURES = ("final_well", "mean_velocity", "locked", "poincare", "lyapunov")
#: fields a grid may run over
GRIDDABLE = ("v0", "theta0", "eps", "damping", "torque", "drive_amplitude", "drive_frequency", "drive_phase",
             "pivot_amplitude", "pivot_frequency", "friction", "drag")
#: The kernel's limits: longer lists and strings are refused with a message, never truncated.
MAX_SWEEP = 4096
MAX_OUTPUTS = 16


class SceneError(ValueError):
    """A malformed scene; the message names the field (and the file and line).

    A subclass of ValueError, raised by :class:`Scene` (and everything that
    builds one) when a field has a wrong type or value, and by
    :meth:`Scene.from_file` / :meth:`Scene.from_namelist` for text that is not
    a valid ``&scene`` group.

    See Also
    --------
    Scene : the fields and their ranges.

    Examples
    --------
    >>> import pendula
    >>> try:
    ...     pendula.Scene(eps=-1.0)
    ... except pendula.SceneError as e:
    ...     print(e)
    field 'eps' must be positive and at most 1e300 (eps = g/l), got -1.0
    """


@dataclass(frozen=True)
class Scene:
    """One pendulum experiment: the system, its initial state, its effects and the output times.

    A frozen dataclass: change fields with :meth:`replace`.  Every field is
    checked when the scene is made; a nonzero effect field names the effect,
    and nothing that is not named is computed.

    Parameters
    ----------
    eps : float
        g / l, the square of the small-oscillation angular frequency (> 0).
        Alternatively give ``g`` and ``length``.
    theta0, v0 : float
        Initial angle (rad) and angular velocity (rad/s) at t = 0.
    t_start, t_end : float
        Time span of the output (may start before 0 and run backwards).
    n_samples : int
        Number of equally spaced output times.
    damping, torque : float
        Linear damping beta and constant torque tau:
        theta'' + beta theta' + eps sin(theta) = tau.
    drive_amplitude, drive_frequency, drive_phase : float
        Periodic drive A cos(Omega t + phase) on the right-hand side.
    cord, guide, gravity : str
        The flexible cord (``cord = 'flexible'``, Garfinkel), the cycloidal
        guide (``guide = 'cycloid'``, Huygens) and non-uniform gravity
        (``gravity = 'inverse-square'`` or ``'linear'``); 'rigid', 'none',
        'uniform' mean absent.
    method : str
        'auto' (exact whenever the scene allows it, otherwise the integrator
        the work-precision study found fastest for the scene's class and rtol),
        'exact', or an integrator.
    rtol, atol, dt : float
        Tolerances of adaptive methods, step of fixed-step ones.
    outputs : tuple of str
        What ``pendula run`` produces: any of trajectory, theta_t, v_t,
        phase, energy, period, omega, theta_max, series, lindstedt, spectrum.
    sweep, sweep_values : str, tuple of float
        Optionally one field and the values it takes, one run per value.
    name : str
        A title for plots and file names.
    cycloid_radius : float
        With guide = 'cycloid': R / l, the radius of the circle generating the
        cheeks and the path (default 1/4: the small-oscillation frequency of
        the rigid pendulum of length l).  The cord is 4R long.
    gravity_distance : float
        With gravity = 'inverse-square': D / l > 1, the distance of the
        attracting point mass below the pivot (g is the strength at the
        lowest point of the circle; uniform as D -> infinity).
    gravity_gradient : float
        With gravity = 'linear': kappa < 1/2 in g(h) = g (1 - kappa h / l),
        h the height above the lowest point (uniform at kappa = 0).
    restitution, max_flips, min_flight : float, int, float
        Flexible cord only: coefficient of restitution of the jerk (0 <= e < 1,
        0 = Garfinkel's inelastic jerk), the most flips simulated (0 <= n <= 1e8),
        and the shortest flight simulated, in units of 1/sqrt(eps) (>= 0): the run
        stops there (later output times are NaN, the stop reason is in the stats).
    grid, grid1, grid2, grid3, grid1_range, grid2_range, grid3_range : tuple
        A grid for :func:`sweep`: the names of 1 to 3 axes, and for each its
        values or (start, stop, count).
    measure : str
        What a grid sweep computes at each point: 'final_well',
        'mean_velocity', 'locked', 'poincare' or 'lyapunov'.
    sweep_t_max, sweep_transient, sweep_samples : float, float, int
        The sweep's time limit (or averaging time), transient and number of
        Poincare samples.
    friction : float
        Dry (Coulomb) friction mu >= 0 at the pivot: -mu sgn(theta') while
        moving; at rest the bob sticks while abs(eps sin(theta) - forces) <= mu
        (static and kinetic coefficients equal).  Stops and restarts are
        events (dopri5 or dop853).
    drag : float
        Quadratic air drag gamma >= 0: -gamma theta' abs(theta').
    pivot_amplitude, pivot_frequency : float
        A vertically vibrating pivot y = a cos(Omega t) (in units of the
        length): the effective gravity eps - a Omega^2 cos(Omega t).  A pivot
        amplitude needs a frequency > 0.
    noise, seed : float, int
        Thermal noise: the temperature T in units of eps (>= 0; needs
        damping > 0, as the force sqrt(2 damping T) xi(t) comes with the
        friction), run by the Langevin integrator (BAOAB, the fixed step
        ``dt``, or when ``dt`` is 0 the shorter of 2 pi / sqrt(eps) and the
        drive period, divided by 100), and the seed of its random numbers
        (0 .. 2^53): the same seed gives the same path, bit for bit.

    Raises
    ------
    SceneError
        For a field of the wrong type or out of its range, naming the field;
        for an unknown field, naming the closest one (``Scene(dampin=0.1)``:
        unknown field 'dampin' (did you mean 'damping'?)).

    See Also
    --------
    simulate : run a scene.
    sweep : a grid of scenes.
    models : which fields select which model.

    Examples
    --------
    >>> import pendula
    >>> s = pendula.Scene(v0=1.9, damping=0.1)
    >>> s.effects, s.is_conservative_rigid
    (('damping',), False)
    >>> s.replace(damping=0.0).is_conservative_rigid
    True
    >>> pendula.Scene.from_namelist("&scene\\n v0 = 1.5\\n/\\n").v0
    1.5
    >>> s                                  # what differs from the defaults
    Scene(v0=1.9, damping=0.1)
    """

    eps: float = math.nan  # not given: 1.0, or g / length when those are given
    theta0: float = 0.0
    v0: float = 0.0
    t_start: float = 0.0
    t_end: float = 20.0
    n_samples: int = 1001
    damping: float = 0.0
    torque: float = 0.0
    drive_amplitude: float = 0.0
    drive_frequency: float = 0.0
    drive_phase: float = 0.0
    cord: str = "rigid"
    guide: str = "none"
    gravity: str = "uniform"
    method: str = "auto"
    rtol: float = 1e-10
    atol: float = 1e-12
    dt: float = 0.0
    outputs: tuple = ("trajectory",)
    sweep: str = ""
    sweep_values: tuple = ()
    name: str = ""
    g: float = field(default=math.nan, repr=False)
    length: float = field(default=math.nan, repr=False)
    # the cycloidal guide and non-uniform gravity
    cycloid_radius: float = 0.25
    gravity_distance: float = 0.0
    gravity_gradient: float = 0.0
    # flexible cord (systems/cord.py)
    restitution: float = 0.0
    max_flips: int = 100000
    min_flight: float = 0.0
    # sweeps over grids: see pendula.sweeps
    grid: tuple = ()
    grid1: tuple = ()
    grid2: tuple = ()
    grid3: tuple = ()
    grid1_range: tuple = ()
    grid2_range: tuple = ()
    grid3_range: tuple = ()
    measure: str = ""
    sweep_t_max: float = 2000.0
    sweep_transient: float = 200.0
    sweep_samples: int = 100
    # effects: dry friction, quadratic drag, a vibrating pivot (guide/effects.md)
    friction: float = 0.0
    drag: float = 0.0
    pivot_amplitude: float = 0.0
    pivot_frequency: float = 0.0
    # thermal noise: the temperature in units of eps, and the seed of its random numbers
    noise: float = 0.0
    seed: int = 0

    def __post_init__(self):
        _check(self)

    # -- construction -------------------------------------------------------
    @classmethod
    def from_file(cls, path: str | os.PathLike[str]) -> "Scene":
        """Read a scene from a namelist file (group ``&scene``).

        The kernel reads and checks the text, as ``pendula-run`` does.

        Parameters
        ----------
        path : str or os.PathLike
            The scene file.

        Returns
        -------
        Scene

        Raises
        ------
        SceneError
            The file cannot be read or holds no valid scene; the message names
            the file, the line and the field.

        Examples
        --------
        >>> import pathlib, tempfile
        >>> p = pathlib.Path(tempfile.mkdtemp()) / "s.nml"
        >>> _ = p.write_text("&scene v0 = 1.5, damping = 0.1 /")
        >>> Scene.from_file(p).effects
        ('damping',)
        """
        source = os.fspath(path)
        if isinstance(source, bytes):
            source = os.fsdecode(source)
        if "\0" in source:
            raise SceneError(f"{source!r}: cannot read scene file (a NUL character in its name)")
        # the kernel reads the file, as pendula-run does: one verdict, one message for every file
        # (a folder, a device such as /dev/zero, a FIFO, UTF-16 text, a NUL byte, more than 16 MiB)
        return cls._from_kernel(_kernel.scene_read_v(b" ", os.fsencode(source), 1), source)

    @classmethod
    def from_namelist(cls, text: str, source: str = "<scene>") -> "Scene":
        """A scene from namelist text, read and checked by the kernel.

        Parameters
        ----------
        text : str
            One namelist group ``&scene ... /``.
        source : str
            Where the text comes from, for messages.

        Returns
        -------
        Scene

        Raises
        ------
        SceneError
            The message names the source, the line and the field.

        Examples
        --------
        >>> Scene.from_namelist("&scene g = 9.81, length = 2.0, method = 'DOP853' /").method
        'dop853'
        >>> Scene.from_namelist("&scene dampin = 0.1 /")
        Traceback (most recent call last):
        ...
        pendula.scene.SceneError: <scene>, line 1: unknown field 'dampin' (did you mean 'damping'?)
        """
        if not isinstance(text, str):
            raise TypeError(f"from_namelist expects the text as a str, got {type(text).__name__}")
        return cls._from_text(text.encode("utf-8", errors="surrogateescape"), str(source))

    @classmethod
    def _from_text(cls, data: bytes, source: str) -> "Scene":
        # f2py passes a string up to its first NUL byte: the kernel's reader sees every byte
        nul = data.find(b"\0")
        if nul >= 0:
            raise SceneError(f"{source}: not a text file (byte {nul + 1} is NUL)")
        return cls._from_kernel(_kernel.scene_read_v(data + b" ", source.encode("utf-8", errors="surrogateescape")),
                                source)

    @classmethod
    def _from_kernel(cls, read: tuple, source: str) -> "Scene":
        """The Scene of what the kernel's reader (scene_read_v, of a text or a file) answered."""
        (x, words, wlen, nout, ngrid, sweep_values, nsweep, grid_values, grid_nv, grid_range, grid_nr, status,
         msg) = read
        if status:
            raise SceneError(_text(msg))
        values = _fields_from_kernel(x, words, wlen, nout, ngrid)
        values["sweep_values"] = tuple(sweep_values[:nsweep].tolist())
        for k in range(3):
            values[f"grid{k + 1}"] = tuple(grid_values[:grid_nv[k], k].tolist())
            values[f"grid{k + 1}_range"] = tuple(grid_range[:grid_nr[k], k].tolist())
        try:
            return cls(**values)
        except SceneError as exc:
            raise SceneError(f"{source}: {exc}") from None

    def replace(self, **changes: Any) -> "Scene":
        """A copy with some fields changed (validated again).

        eps, g and length stay consistent: changing eps alone drops g and
        length (eps is then what was given); changing g or length recomputes
        eps from them.

        Parameters
        ----------
        **changes
            Field names and their new values.

        Returns
        -------
        Scene

        Raises
        ------
        SceneError
            For an unknown field or a bad value.

        Examples
        --------
        >>> import pendula
        >>> pendula.Scene(v0=1.0).replace(damping=0.1).effects
        ('damping',)
        """
        if "eps" in changes and not ("g" in changes or "length" in changes):
            changes.setdefault("g", math.nan)
            changes.setdefault("length", math.nan)
        elif ("g" in changes or "length" in changes) and "eps" not in changes:
            changes["eps"] = math.nan
        _refuse_unknown(changes)
        return dataclasses.replace(self, **changes)

    def __repr__(self) -> str:
        """``Scene(...)`` with the fields that differ from the defaults (what ``Scene(...)`` needs to remake it)."""
        return "Scene(" + ", ".join(f"{k}={v!r}" for k, v in self._changed().items()) + ")"

    def _changed(self) -> dict:
        """The fields that differ from a default Scene's, in field order (g and length when given)."""
        base = _default_scene()
        out = {}
        for f in fields(self):
            v = getattr(self, f.name)
            ref = getattr(base, f.name)
            same = (v == ref) or (isinstance(v, float) and isinstance(ref, float) and v != v and ref != ref)
            if f.name == "eps" and not math.isnan(self.g):
                continue   # eps follows from g and length, which are shown
            if not same:
                out[f.name] = v
        return out

    # -- what the scene asks for -------------------------------------------
    @property
    def effects(self) -> tuple[str, ...]:
        """The effects this scene names, in a fixed order."""
        known = self.__dict__.get("_effects")
        if known is not None:   # formed once per (frozen) scene
            return known
        out = []
        if self.damping != 0.0:
            out.append("damping")
        if self.torque != 0.0:
            out.append("torque")
        if self.drive_amplitude != 0.0:
            out.append("drive")
        if self.cord != "rigid":
            out.append("cord")
        if self.guide != "none":
            out.append("guide")
        if self.gravity != "uniform":
            out.append("gravity")
        out += [name for name, on in (("friction", self.friction), ("drag", self.drag),
                                      ("pivot", self.pivot_amplitude)) if on != 0.0]
        if self.noise != 0.0:
            out.append("noise")
        object.__setattr__(self, "_effects", tuple(out))
        return self._effects

    @property
    def is_conservative_rigid(self) -> bool:
        """True when the exact elliptic-function solution answers this scene."""
        return not self.effects

    def members(self) -> list["Scene"]:
        """One scene per sweep value (the scene itself when there is no sweep).

        Returns
        -------
        list of Scene

        Examples
        --------
        >>> import pendula
        >>> [m.v0 for m in pendula.Scene(sweep="v0", sweep_values=(1.0, 2.0)).members()]
        [1.0, 2.0]
        """
        if not self.sweep:
            return [self]
        # series and lindstedt compare the members over the sweep: a member alone has neither
        one = tuple(o for o in self.outputs if o not in ("series", "lindstedt")) or ("trajectory",)
        return [self.replace(**{self.sweep: float(v)}, sweep="", sweep_values=(), outputs=one)
                for v in self.sweep_values]

    def times(self) -> np.ndarray:
        """The output times: n_samples points from t_start to t_end (a new array each call)."""
        t = self.__dict__.get("_times")
        if t is None:   # formed once per (frozen) scene
            t = np.linspace(self.t_start, self.t_end, self.n_samples)
            object.__setattr__(self, "_times", t)
        return t.copy()

    def to_namelist(self) -> str:
        """The scene as namelist text (what :meth:`from_namelist` reads back).

        Returns
        -------
        str

        Examples
        --------
        >>> import pendula
        >>> s = pendula.Scene(v0=1.5)
        >>> pendula.Scene.from_namelist(s.to_namelist()) == s
        True
        """
        lines = ["&scene"]
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name in ("g", "length"):
                continue
            if isinstance(v, tuple):
                if not v:
                    continue
                lines.append(f"  {f.name} = " + ", ".join(_fmt(x) for x in v))
            else:
                lines.append(f"  {f.name} = {_fmt(v)}")
        lines.append("/")
        return "\n".join(lines) + "\n"


#: every field a Scene takes, for the check of keyword names
_FIELD_NAMES = tuple(f.name for f in fields(Scene))


def _unknown_field(name: str) -> str:
    """The message for a field a Scene does not have, with the closest name when one is close."""
    close = difflib.get_close_matches(str(name), _FIELD_NAMES, n=1, cutoff=0.75)
    hint = f" (did you mean '{close[0]}'?)" if close else ""
    return f"unknown field '{name}'{hint}"


def _refuse_unknown(names) -> None:
    for name in names:
        if name not in _FIELD_NAMES:
            raise SceneError(_unknown_field(name))


_dataclass_init = Scene.__init__


@functools.wraps(_dataclass_init)
def _init(self, *args, **kwargs):
    _refuse_unknown(kwargs)   # before the dataclass's own TypeError: a SceneError naming the field
    _dataclass_init(self, *args, **kwargs)


Scene.__init__ = _init


@functools.lru_cache(maxsize=1)
def _default_scene() -> Scene:
    return Scene()


def _fmt(v) -> str:
    if isinstance(v, str):
        return "'" + v.replace("'", "''") + "'"
    if isinstance(v, bool):
        return ".true." if v else ".false."
    if isinstance(v, int):
        return str(v)
    return repr(float(v))


# ---------------------------------------------------------------- the kernel's check

def _text(b) -> str:
    return (b.decode("utf-8", errors="replace") if isinstance(b, bytes) else str(b)).strip()


def _layout():
    names = _text(_kernel.scene_layout_v())
    numbers, words = names.split("|")
    return tuple(numbers.split()), tuple(words.split())


#: the scene's numbers and single words in the kernel's order (kernel/io/pendula_scene.f90)
_NUMBERS, _WORDS = _layout()
_WHOLE = ("n_samples", "max_flips", "sweep_samples", "seed")
_STRING_LISTS = ("outputs", "grid")
_EMPTY = np.zeros(0)
_NUMBER_LISTS = ("sweep_values", "grid1", "grid2", "grid3", "grid1_range", "grid2_range", "grid3_range")


def _number(name, v) -> float:
    """A field's value as a double (a conversion: the kernel holds the rules)."""
    if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
        kind = "a whole number" if name in _WHOLE else "a real number"
        raise SceneError(f"field '{name}' must be {kind}, got {v!r}")
    try:
        return float(v)
    except OverflowError:
        raise SceneError(f"field '{name}' is too large for a double: {v!r}") from None


def _as_list(name, v, kind) -> tuple:
    if type(v) is tuple and all(type(x) is (str if kind is str else float) for x in v):
        return v
    if isinstance(v, (str, bytes, int, float, np.integer, np.floating)):
        v = (v,)
    elif isinstance(v, np.ndarray):
        v = v.reshape(-1).tolist()
    try:
        items = tuple(v)
    except TypeError:
        raise SceneError(f"field '{name}' must be a list of {'strings' if kind is str else 'numbers'}, "
                         f"got {v!r}") from None
    if kind is str:
        for x in items:
            if not isinstance(x, str):
                raise SceneError(f"field '{name}' must be a list of strings, got {x!r}")
        return items
    return tuple(_number(name, x) for x in items)


def _fields_from_kernel(x, words, wlen, nout, ngrid) -> dict:
    """The Scene's fields from the numbers and words the kernel returns."""
    raw = words if isinstance(words, bytes) else str(words).encode("utf-8")
    out, at = [], 0
    for n in wlen[:len(_WORDS) + nout + ngrid]:
        out.append(raw[at:at + n].decode("utf-8", errors="surrogateescape"))
        at += n
    # NaN (g and length not given) as the one math.nan, so that equal scenes compare equal
    values = {name: (int(v) if name in _WHOLE else (v if v == v else math.nan))
              for name, v in zip(_NUMBERS, np.asarray(x, dtype=np.float64).tolist())}
    values.update(zip(_WORDS, out))
    values["outputs"] = tuple(out[len(_WORDS):len(_WORDS) + nout])
    values["grid"] = tuple(out[len(_WORDS) + nout:])
    return values


def _check(s: Scene) -> None:
    """Check a new Scene with the kernel's rules; set its fields to the
    checked ones (eps settled, words in lower case, the default output) and
    keep them, as the kernel takes them, for every run of the scene."""
    d = s.__dict__
    x = np.array([v if type(v) is float else _number(name, v) for name, v in ((n, d[n]) for n in _NUMBERS)],
                 dtype=np.float64)
    singles = []
    for name in _WORDS:
        v = d[name]
        if type(v) is not str:
            raise SceneError(f"field '{name}' must be a string, got {v!r}")
        singles.append(v)
    outputs = _as_list("outputs", d["outputs"], str)
    grid = _as_list("grid", d["grid"], str)
    # the words reach the kernel as one string, which f2py cuts at a NUL: refused here, naming the field
    for name, ws in list(zip(_WORDS, ([w] for w in singles))) + [("outputs", outputs), ("grid", grid)]:
        if any("\0" in w for w in ws):
            raise SceneError(f"field '{name}' must not hold a NUL character, got {tuple(ws) if len(ws) > 1 else ws[0]!r}")
    lists = {name: (() if d[name] == () else _as_list(name, d[name], float)) for name in _NUMBER_LISTS}
    encoded = [w.encode("utf-8", errors="surrogateescape") for w in singles + list(outputs) + list(grid)]
    wlen = np.array([len(w) for w in encoded], dtype=np.int32)
    arrays = [_EMPTY if not lists[name] else np.array(lists[name], dtype=np.float64) for name in _NUMBER_LISTS]
    x_out, words_out, wlen_out, nout, ngrid, status, msg = _kernel.scene_check_v(
        x, b"".join(encoded) + b" ", wlen, len(outputs), len(grid), *arrays)
    if status:
        raise SceneError(_text(msg))
    values = _fields_from_kernel(x_out, words_out, wlen_out, nout, ngrid)
    values.update(lists)
    d.update(values)   # the frozen dataclass's fields, set once here
    n = len(_WORDS) + int(nout) + int(ngrid)
    raw = words_out if isinstance(words_out, bytes) else str(words_out).encode("utf-8")
    d["_kernel_fields"] = (x_out, raw[:int(np.sum(wlen_out[:n]))] + b" ",
                           np.ascontiguousarray(wlen_out[:n], dtype=np.int32), int(nout), int(ngrid))
