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

The same file is read by Python (:meth:`Scene.from_file`) and natively by the
compiled batch executable ``pendula-run``.  A scene names the effects it wants
by giving their parameters (``damping``, ``torque``, ``drive_amplitude`` ...);
effects it does not name are not in the model, and a conservative rigid
pendulum is answered by the exact solution.  A field that is unknown,
misspelled, of the wrong type or out of range is an error that names it.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import pathlib
import re
from dataclasses import dataclass, field, fields

import numpy as np

#: Trajectory columns and derived outputs a scene may ask for.
OUTPUTS = ("trajectory", "theta_t", "v_t", "phase", "energy", "period", "omega", "theta_max",
           "series", "lindstedt", "spectrum")
#: Methods (issue "Integrators" adds the numerical ones).
METHODS = ("auto", "exact", "rk4", "verlet", "yoshida4", "yoshida6", "yoshida8", "gauss4", "gauss6",
           "dopri5", "dop853", "gsl-rk8pd", "dprkn6", "vern9")
CORDS = ("rigid", "flexible")
GUIDES = ("none", "cycloid")
GRAVITIES = ("uniform", "inverse-square", "linear")
SWEEPABLE = ("v0", "theta0", "eps", "damping", "torque", "drive_amplitude", "drive_frequency")
#: Limits shared with the kernel's reader (kernel/io/pendula_scene.f90): longer
#: lists and strings are refused with a message, never truncated.
MAX_SWEEP = 4096
MAX_OUTPUTS = 16
STR_LIMITS = {"name": 256, "cord": 32, "guide": 32, "gravity": 32, "method": 32, "sweep": 32, "measure": 32}
OUTPUT_LIMIT = 16


class SceneError(ValueError):
    """A malformed scene; the message names the field (and the file and line)."""


@dataclass(frozen=True)
class Scene:
    """One pendulum experiment.

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
        Room for the flexible cord (Garfinkel), the cycloidal guide (Huygens)
        and non-uniform gravity; 'rigid', 'none', 'uniform' mean absent.
    method : str
        'auto' (exact whenever the scene allows it), 'exact', or an integrator.
    rtol, atol, dt : float
        Tolerances of adaptive methods, step of fixed-step ones.
    outputs : tuple of str
        What to produce: see :data:`OUTPUTS`.
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
    # issue 13: the cycloidal guide and non-uniform gravity
    cycloid_radius: float = 0.25
    gravity_distance: float = 0.0
    gravity_gradient: float = 0.0
    # flexible cord (systems/cord.py)
    restitution: float = 0.0
    max_flips: int = 100000
    min_flight: float = 0.0
    # sweeps over grids (issue 14): see pendula.sweeps
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

    def __post_init__(self):
        _validate(self)

    # -- construction -------------------------------------------------------
    @classmethod
    def from_file(cls, path) -> "Scene":
        """Read a scene from a namelist file (group ``&scene``)."""
        path = pathlib.Path(path)
        try:
            data = path.read_bytes()
        except OSError as exc:
            raise SceneError(f"{path}: cannot read scene file: {exc.strerror}") from None
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise SceneError(f"{path}: not UTF-8 text (byte {exc.start + 1} is not part of a UTF-8 character)") \
                from None
        return cls.from_namelist(text, source=str(path))

    @classmethod
    def from_namelist(cls, text: str, source: str = "<scene>") -> "Scene":
        """Parse namelist text; errors name the source, the line and the field."""
        values = parse_namelist(text, source)
        try:
            return cls(**values)
        except SceneError as exc:
            raise SceneError(f"{source}: {exc}") from None

    def replace(self, **changes) -> "Scene":
        """A copy with some fields changed (validated again).

        eps, g and length stay consistent: changing eps alone drops g and
        length (eps is then what was given); changing g or length recomputes
        eps from them.
        """
        if "eps" in changes and not ("g" in changes or "length" in changes):
            changes.setdefault("g", math.nan)
            changes.setdefault("length", math.nan)
        elif ("g" in changes or "length" in changes) and "eps" not in changes:
            changes["eps"] = math.nan
        return dataclasses.replace(self, **changes)

    # -- what the scene asks for -------------------------------------------
    @property
    def effects(self) -> tuple[str, ...]:
        """The effects this scene names, in a fixed order."""
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
        return tuple(out)

    @property
    def is_conservative_rigid(self) -> bool:
        """True when the exact elliptic-function solution answers this scene."""
        return not self.effects

    def members(self) -> list["Scene"]:
        """One scene per sweep value (the scene itself when there is no sweep)."""
        if not self.sweep:
            return [self]
        return [self.replace(**{self.sweep: float(v)}, sweep="", sweep_values=()) for v in self.sweep_values]

    def times(self) -> np.ndarray:
        """The output times: n_samples points from t_start to t_end."""
        return np.linspace(self.t_start, self.t_end, self.n_samples)

    def to_namelist(self) -> str:
        """The scene as namelist text (what from_namelist reads back)."""
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


def _fmt(v) -> str:
    if isinstance(v, str):
        return "'" + v.replace("'", "''") + "'"
    if isinstance(v, bool):
        return ".true." if v else ".false."
    if isinstance(v, int):
        return str(v)
    return repr(float(v))


# ---------------------------------------------------------------- validation

_FLOATS = {"eps", "theta0", "v0", "t_start", "t_end", "damping", "torque", "drive_amplitude",
           "drive_frequency", "drive_phase", "rtol", "atol", "dt", "g", "length",
           "cycloid_radius", "gravity_distance", "gravity_gradient", "restitution", "min_flight",
           "sweep_t_max", "sweep_transient"}
_INTS = {"n_samples", "max_flips", "sweep_samples"}
_STRS = {"cord", "guide", "gravity", "method", "sweep", "name", "measure"}
_TUPLES = {"outputs": str, "sweep_values": float, "grid": str, "grid1": float, "grid2": float, "grid3": float,
           "grid1_range": float, "grid2_range": float, "grid3_range": float}
#: what a sweep point can answer (see pendula.sweeps)
MEASURES = ("final_well", "mean_velocity", "locked", "poincare", "lyapunov")
#: fields a grid may run over
GRIDDABLE = ("v0", "theta0", "eps", "damping", "torque", "drive_amplitude", "drive_frequency", "drive_phase")


def _validate(s: Scene) -> None:
    set_ = object.__setattr__
    for name in _FLOATS:
        v = getattr(s, name)
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
            raise SceneError(f"field '{name}' must be a real number, got {v!r}")
        try:
            set_(s, name, float(v))
        except OverflowError:
            raise SceneError(f"field '{name}' is too large for a double: {v!r}") from None
        if name not in ("g", "length", "eps") and not math.isfinite(float(v)):
            raise SceneError(f"field '{name}' must be finite, got {v!r}")
    for name in sorted(_INTS):
        v = getattr(s, name)
        if isinstance(v, bool) or not isinstance(v, (int, np.integer)) and not (isinstance(v, float) and v.is_integer()):
            raise SceneError(f"field '{name}' must be a whole number, got {v!r}")
        set_(s, name, int(v))
    for name in _STRS:
        v = getattr(s, name)
        if not isinstance(v, str):
            raise SceneError(f"field '{name}' must be a string, got {v!r}")
        if len(v) > STR_LIMITS[name]:
            raise SceneError(f"field '{name}' is longer than {STR_LIMITS[name]} characters")
        if name != "name":  # words are case-insensitive, as Fortran names are
            set_(s, name, v.lower())
    for name, kind in _TUPLES.items():
        v = getattr(s, name)
        if isinstance(v, (str, float, int, np.floating)):
            v = (v,)
        v = tuple(np.asarray(v).tolist()) if isinstance(v, np.ndarray) else tuple(v)
        for x in v:
            ok = isinstance(x, str) if kind is str else (
                isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, bool))
            if not ok:
                raise SceneError(f"field '{name}' must be a list of "
                                 f"{'strings' if kind is str else 'numbers'}, got {x!r}")
        try:
            set_(s, name, tuple(kind(x) for x in v))
        except OverflowError:
            raise SceneError(f"field '{name}' holds a number too large for a double") from None
    if len(s.sweep_values) > MAX_SWEEP:
        raise SceneError(f"field 'sweep_values' holds {len(s.sweep_values)} values; at most {MAX_SWEEP}")
    if len(s.outputs) > MAX_OUTPUTS:
        raise SceneError(f"field 'outputs' names {len(s.outputs)} outputs; at most {MAX_OUTPUTS}")
    set_(s, "outputs", tuple(o.lower() for o in s.outputs))
    # g and length: both or neither, and then eps = g / length (a given eps must agree)
    if math.isnan(s.g) != math.isnan(s.length):
        raise SceneError("fields 'g' and 'length' go together (eps = g / length): give both or neither")
    if not math.isnan(s.g):
        if not (s.g > 0 and s.length > 0 and math.isfinite(s.g) and math.isfinite(s.length)):
            raise SceneError("fields 'g' and 'length' must be positive and finite")
        if not math.isnan(s.eps) and s.eps != s.g / s.length:
            raise SceneError(f"fields 'eps' = {s.eps!r} and 'g' / 'length' = {s.g / s.length!r} contradict "
                             "each other: give eps, or g and length")
        set_(s, "eps", s.g / s.length)
    elif math.isnan(s.eps):
        set_(s, "eps", 1.0)
    if not math.isfinite(s.eps):
        raise SceneError(f"field 'eps' must be finite, got {s.eps!r}")
    if not s.eps > 0:
        raise SceneError(f"field 'eps' must be positive (eps = g/l), got {s.eps!r}")
    if s.n_samples < 1 or s.n_samples > 100_000_000:
        raise SceneError(f"field 'n_samples' must be between 1 and 1e8, got {s.n_samples}")
    if s.damping < 0:
        raise SceneError(f"field 'damping' must be >= 0, got {s.damping!r}")
    if s.drive_frequency < 0:
        raise SceneError(f"field 'drive_frequency' must be >= 0, got {s.drive_frequency!r}")
    if s.rtol <= 0 or s.atol < 0:
        raise SceneError("fields 'rtol' must be > 0 and 'atol' >= 0")
    if s.dt < 0:
        raise SceneError(f"field 'dt' must be >= 0 (0: chosen by the method), got {s.dt!r}")
    if not 0.0 <= s.restitution < 1.0:
        raise SceneError(f"field 'restitution' must be in [0, 1), got {s.restitution!r}")
    if not 0 <= s.max_flips <= 100_000_000:
        raise SceneError(f"field 'max_flips' must be between 0 and 1e8, got {s.max_flips}")
    if s.min_flight < 0:
        raise SceneError(f"field 'min_flight' must be >= 0, got {s.min_flight!r}")
    for name, allowed in (("cord", CORDS), ("guide", GUIDES), ("gravity", GRAVITIES), ("method", METHODS)):
        if getattr(s, name) not in allowed:
            raise SceneError(f"field '{name}' must be one of {', '.join(allowed)}; got {getattr(s, name)!r}"
                             + _suggest(getattr(s, name), allowed))
    for o in s.outputs:
        if o not in OUTPUTS:
            raise SceneError(f"field 'outputs': unknown output {o!r}; known: {', '.join(OUTPUTS)}"
                             + _suggest(o, OUTPUTS))
    if s.sweep:
        if s.sweep not in SWEEPABLE:
            raise SceneError(f"field 'sweep' must name one of {', '.join(SWEEPABLE)}; got {s.sweep!r}")
        if not s.sweep_values:
            raise SceneError("field 'sweep_values' is empty but 'sweep' names a field")
        if not all(math.isfinite(x) for x in s.sweep_values):
            raise SceneError("field 'sweep_values' must be finite numbers")
        rule = _MEMBER_RULES.get(s.sweep)
        if rule:
            bad = [x for x in s.sweep_values if not rule[0](x)]
            if bad:
                raise SceneError(f"field 'sweep_values': {s.sweep} = {bad[0]!r} is out of range ({rule[1]})")
    elif s.sweep_values:
        raise SceneError("field 'sweep_values' is given but 'sweep' does not name a field")
    _validate_issue13(s)
    _validate_grid(s)
    if s.method == "exact" and [e for e in s.effects
                                if e != "guide" and not (e == "cord" and s.cord == "flexible")]:
        raise SceneError(f"field 'method': 'exact' answers only the conservative rigid pendulum, "
                         f"but the scene names {', '.join(s.effects)}")


#: the range rule of each sweepable field (the same as for the field itself)
_MEMBER_RULES = {"eps": (lambda x: x > 0, "eps must be > 0"),
                 "damping": (lambda x: x >= 0, "damping must be >= 0"),
                 "drive_frequency": (lambda x: x >= 0, "drive_frequency must be >= 0")}


def _validate_issue13(s: Scene) -> None:
    """The cycloidal guide and the gravity fields (issue 13); same rules in pendula_scene.f90."""
    if not s.cycloid_radius > 0:
        raise SceneError(f"field 'cycloid_radius' must be positive (R / l), got {s.cycloid_radius!r}")
    if s.guide != "cycloid" and s.cycloid_radius != 0.25:
        raise SceneError("field 'cycloid_radius' is used only with guide = 'cycloid'")
    if s.gravity == "inverse-square":
        if not s.gravity_distance > 1:
            raise SceneError("field 'gravity_distance' (D / l, the point mass below the pivot) must be > 1 "
                             f"with gravity = 'inverse-square', got {s.gravity_distance!r}")
    elif s.gravity_distance != 0.0:
        raise SceneError("field 'gravity_distance' is used only with gravity = 'inverse-square'")
    if s.gravity == "linear":
        if not s.gravity_gradient < 0.5:
            raise SceneError("field 'gravity_gradient' (kappa in g (1 - kappa h / l)) must be < 0.5 "
                             f"so that gravity points down at the top, got {s.gravity_gradient!r}")
    elif s.gravity_gradient != 0.0:
        raise SceneError("field 'gravity_gradient' is used only with gravity = 'linear'")
    if s.guide == "cycloid":
        if s.cord != "rigid":
            raise SceneError("field 'cord': the cycloidal guide wraps an inextensible cord of length 4R; "
                             "cord = 'flexible' has no meaning on it")
        if s.gravity != "uniform":
            raise SceneError("field 'gravity': the cycloidal guide is isochronous only in uniform gravity; "
                             "non-uniform gravity with guide = 'cycloid' is not a model of pendula")
        if s.method not in ("auto", "exact"):
            raise SceneError(f"field 'method': the cycloidal pendulum is solved in closed form "
                             f"(method 'auto' or 'exact'), never integrated; got {s.method!r}")
        if not abs(s.theta0) <= math.pi / 2:
            raise SceneError(f"field 'theta0': on the cycloid |theta0| <= pi/2 (the cusps, |s| = 4R), "
                             f"got {s.theta0!r}")


def _validate_grid(s: Scene) -> None:
    """Sweep grid fields (issue 14); the Fortran reader applies the same rules."""
    if len(s.grid) > 3:
        raise SceneError(f"field 'grid' names at most 3 axes, got {len(s.grid)}")
    if len(set(s.grid)) != len(s.grid):
        raise SceneError("field 'grid' names an axis twice")
    for g in s.grid:
        if g not in GRIDDABLE:
            raise SceneError(f"field 'grid': cannot sweep {g!r}; one of {', '.join(GRIDDABLE)}" + _suggest(g, GRIDDABLE))
    for k in (1, 2, 3):
        vals, rng = getattr(s, f"grid{k}"), getattr(s, f"grid{k}_range")
        if k > len(s.grid):
            if vals or rng:
                raise SceneError(f"field 'grid{k}' or 'grid{k}_range' is given but 'grid' names {len(s.grid)} axes")
            continue
        if bool(vals) == bool(rng):
            raise SceneError(f"axis {k} ('{s.grid[k - 1]}'): give exactly one of 'grid{k}' (values) "
                             f"or 'grid{k}_range' (start, stop, count)")
        if not all(math.isfinite(x) for x in vals + rng):
            raise SceneError(f"field 'grid{k}{'_range' if rng else ''}' must be finite numbers")
        if rng and (len(rng) != 3 or not float(rng[2]).is_integer() or not 1 <= rng[2] <= 1e8):
            raise SceneError(f"field 'grid{k}_range' must be start, stop, count (count a whole number >= 1)")
    if s.measure and s.measure not in MEASURES:
        raise SceneError(f"field 'measure' must be one of {', '.join(MEASURES)}; got {s.measure!r}"
                         + _suggest(s.measure, MEASURES))
    if s.grid and not s.measure:
        raise SceneError("field 'grid' is given but 'measure' is not")
    if not s.sweep_t_max > 0:
        raise SceneError(f"field 'sweep_t_max' must be > 0, got {s.sweep_t_max!r}")
    if s.sweep_transient < 0:
        raise SceneError(f"field 'sweep_transient' must be >= 0, got {s.sweep_transient!r}")
    if not 1 <= s.sweep_samples <= 10_000_000:
        raise SceneError(f"field 'sweep_samples' must be between 1 and 1e7, got {s.sweep_samples}")


def _suggest(word, choices) -> str:
    close = difflib.get_close_matches(str(word), list(choices), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


# ---------------------------------------------------------------- namelist

_TOKEN = re.compile(r"""
    (?P<rep>\d+\*)
  | (?P<str>'(?:[^']|'')*'|"(?:[^"]|"")*")
  | (?P<logical>\.(?:true|false|t|f)\.)
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<num>[+-]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][+-]?\d+)?)
  | (?P<eq>=)
  | (?P<sep>,)
  | (?P<end>/)
  | (?P<group>&[A-Za-z_]+)
  | (?P<space>\s+)
  | (?P<comment>![^\n]*)
""", re.VERBOSE | re.IGNORECASE)

_FIELDS = {f.name for f in fields(Scene)}


def parse_namelist(text: str, source: str = "<scene>") -> dict:
    """The ``&scene`` group of a namelist as a dict of Scene fields.

    Supports what the scenes use: scalars, comma- or blank-separated lists,
    quoted strings, logicals, ``!`` comments.  Field names are case-insensitive
    (as in Fortran).  Anything else is a SceneError naming line and field.
    """
    pos, line = 0, 1
    tokens = []
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if not m:
            bad = text[pos:].split()[0] if text[pos:].split() else text[pos]
            raise SceneError(f"{source}, line {line}: cannot read {bad!r}")
        kind = m.lastgroup
        if kind not in ("space", "comment"):
            tokens.append((kind, m.group(), line))
        line += m.group().count("\n")
        pos = m.end()
    if not tokens or tokens[0][0] != "group" or tokens[0][1].lower() != "&scene":
        raise SceneError(f"{source}: a scene file must start with the group '&scene'")
    ends = [k for k, tok in enumerate(tokens) if tok[0] == "end"]
    if not ends:
        raise SceneError(f"{source}: the group '&scene' is not closed with '/'")
    if ends[0] != len(tokens) - 1:
        kind, tok, ln = tokens[ends[0] + 1]
        raise SceneError(f"{source}, line {ln}: text after the end '/' of the group '&scene' ({tok!r}); "
                         "a scene file holds one group")
    values: dict = {}
    i = 1
    body = tokens[1:-1]
    while i - 1 < len(body):
        kind, tok, ln = body[i - 1]
        if kind == "sep":
            i += 1
            continue
        if kind != "name":
            raise SceneError(f"{source}, line {ln}: expected a field name, got {tok!r}")
        key = tok.lower()
        if key not in _FIELDS:
            raise SceneError(f"{source}, line {ln}: unknown field '{tok}'" + _suggest(key, sorted(_FIELDS)))
        if key in values:
            raise SceneError(f"{source}, line {ln}: field '{key}' is given twice")
        if i >= len(body) or body[i][0] != "eq":
            raise SceneError(f"{source}, line {ln}: field '{key}' must be followed by '='")
        i += 2
        items = []
        repeat = 0
        if i - 1 < len(body) and body[i - 1][0] == "sep":
            raise SceneError(f"{source}, line {ln}: field '{key}' has no value")
        while i - 1 < len(body):
            k2, t2, l2 = body[i - 1]
            if k2 == "sep":
                if repeat:
                    raise SceneError(f"{source}, line {l2}: field '{key}': a repeat count needs a value")
                i += 1
                continue
            if k2 == "name" and i < len(body) and body[i][0] == "eq":
                if repeat:
                    raise SceneError(f"{source}, line {l2}: field '{key}': a repeat count needs a value")
                break
            if k2 == "rep":
                if repeat:
                    raise SceneError(f"{source}, line {l2}: field '{key}': cannot read value {t2!r}")
                repeat = int(t2[:-1])
                if not 1 <= repeat <= MAX_SWEEP:
                    raise SceneError(f"{source}, line {l2}: field '{key}': repeat count {repeat} out of range")
                i += 1
                continue
            n_before = len(items)
            if k2 == "str":
                q = t2[0]
                items.append(t2[1:-1].replace(q + q, q))
            elif k2 == "num":
                items.append(float(t2.lower().replace("d", "e")) if re.search(r"[.eEdD]", t2) else int(t2))
            elif k2 == "logical":
                items.append(t2.lower() in (".true.", ".t."))
            else:
                raise SceneError(f"{source}, line {l2}: field '{key}': cannot read value {t2!r}")
            if repeat:
                items.extend(items[n_before:] * (repeat - 1))
                repeat = 0
            i += 1
        if repeat:
            raise SceneError(f"{source}, line {ln}: field '{key}': a repeat count needs a value")
        if not items:
            raise SceneError(f"{source}, line {ln}: field '{key}' has no value")
        if key in _TUPLES:
            values[key] = tuple(items)
        elif len(items) > 1:
            raise SceneError(f"{source}, line {ln}: field '{key}' takes one value, got {len(items)}")
        else:
            v = items[0]
            if key in _FLOATS and isinstance(v, int) and not isinstance(v, bool):
                v = float(v)
            if key in _FLOATS and not isinstance(v, float):
                raise SceneError(f"{source}, line {ln}: field '{key}' must be a real number, got {v!r}")
            if key in _STRS and not isinstance(v, str):
                raise SceneError(f"{source}, line {ln}: field '{key}' must be a quoted string, got {v!r}")
            if key in _INTS and not isinstance(v, int):
                raise SceneError(f"{source}, line {ln}: field '{key}' must be a whole number, got {v!r}")
            values[key] = v
    return values
