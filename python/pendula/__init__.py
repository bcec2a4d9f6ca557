"""pendula: the nonlinear pendulum and its relatives.

Exact where exactness is possible (Jacobi elliptic functions for the
conservative pendulum), fast everywhere (a Fortran kernel), and honest about
what accuracy costs.

Elliptic functions
------------------
ellipk, ellipe, ellipf, ellipeinc, ellipj, nome

The pendulum
------------
Scene, simulate, period, orbit, exact_motion, energy,
period_series, period_from_series, poincare_lindstedt

Integration and events
----------------------
simulate(scene, method=...), find_events, numerical_period

Spectra
-------
spectrum, spectra, fourier_series, odd_harmonics_above

Figures
-------
pendula.plot: trajectory, phase, spectrum, bifurcation, basins, iv, fractions

Laboratory units
----------------
Pendulum (metres, seconds, degrees; pendula.plot.animate draws it), Swing,
Junction (amperes, volts)
"""

from . import _kernel as _k

_k.gsl_init()  # GSL must never abort the process: switch its handler off once
del _k

from .density import angle_cdf, angle_density, arcsine_density  # noqa: E402
from .elliptic import ellipe, ellipeinc, ellipf, ellipj, ellipk, nome  # noqa: E402
from .integrate import Events, find_events, numerical_period  # noqa: E402
from .motion import Orbit, Trajectory, energy, exact_motion, orbit, period, simulate  # noqa: E402
from .scene import Scene, SceneError  # noqa: E402
from .series import period_from_series, period_series, poincare_lindstedt  # noqa: E402
from .systems import ModelInfo, models  # noqa: E402
from .systems.contract import Capability, NetworkTimeScales, TimeScales, capabilities, time_scales  # noqa: E402
from .spectrum import FourierSeries, Spectrum, fourier_series, odd_harmonics_above, spectra, spectrum  # noqa: E402

# Huygens' cycloidal pendulum, non-uniform gravity, the density of the angle
from .systems.cycloid import CycloidGeometry, cycloid_geometry, cycloid_period  # noqa: E402
from .systems.gravity import gravity_orbit  # noqa: E402
from .systems.cord import cord_state, flip_map, flip_sequence  # noqa: E402
from .systems.friction import FrictionTurningPoints, friction_turning_points  # noqa: E402
# sweeps over parameter grids; xarray is imported only when a sweep runs
from .sweeps import sweep  # noqa: E402
from .ivcurve import iv_curve  # noqa: E402
# the Josephson junction in laboratory units (RCSJ on the pendulum)
from .junction import Junction, SwitchingCurrents  # noqa: E402
from .dynamics import Equilibrium, PeriodicOrbit, attractor_continuation, attractor_map, equilibria, periodic_orbit  # noqa: E402,E501
from .dynamics import (Bifurcation, Branch, BranchTree, ContinuationError, EquilibriumBranch,  # noqa: E402
                       bifurcation_tree, continue_equilibria, continue_orbit)
from .dynamics import BifurcationCurve, CodimTwoPoint, ShapiroTongue, continue_bifurcation, shapiro_tongue  # noqa: E402,E501
from .dynamics import WadaTest, kaplan_yorke_dimension, wada_test  # noqa: E402
from .spectrum import precompute_wisdom, wisdom_path  # noqa: E402
from .laboratory import Pendulum, Swing  # noqa: E402
# the quantum pendulum: Mathieu characteristic values and the transmon
from .quantum import Transmon, mathieu_a, mathieu_b, mathieu_ce, mathieu_exponent, mathieu_se  # noqa: E402
from .mathieu_floquet import mathieu_me  # noqa: E402
# networks of pendula: coupled phases, chains, arrays of junctions
from .systems.network import Network, NetworkEquilibrium, NormalModes, network_time_scales  # noqa: E402
from .squid import DCSquid  # noqa: E402
from .long_junction import fluxon_velocity  # noqa: E402
from .rf_squid import RFSquid  # noqa: E402

# the junction in the laboratory: escape and switching at any ramp rate, rf as the source states it
from .escape import (SwitchingDistribution, crossover_temperature, escape_rate, quantum_rate,  # noqa: E402
                     switching_distribution, thermal_rate)
from .rf import rf_current  # noqa: E402

# the version of the installed metadata (written once, in meson.build)
from ._version import __version__  # noqa: E402

__all__ = ["ellipk", "ellipe", "ellipf", "ellipeinc", "ellipj", "nome",
           "Scene", "SceneError", "simulate", "period", "orbit", "exact_motion", "energy",
           "Orbit", "Trajectory", "period_series", "period_from_series", "poincare_lindstedt",
           "find_events", "numerical_period", "Events",
           "spectrum", "spectra", "Spectrum", "fourier_series", "FourierSeries", "odd_harmonics_above",
           "models", "ModelInfo", "capabilities", "Capability", "time_scales", "TimeScales", "network_time_scales", "NetworkTimeScales", "cycloid_geometry", "cycloid_period", "CycloidGeometry", "gravity_orbit",
           "angle_density", "angle_cdf", "arcsine_density", "flip_map", "cord_state", "flip_sequence",
           "sweep", "iv_curve",
           "precompute_wisdom", "wisdom_path",
           "equilibria", "Equilibrium", "periodic_orbit", "PeriodicOrbit", "attractor_map",
           "friction_turning_points", "FrictionTurningPoints",
           "Junction", "SwitchingCurrents", "attractor_continuation",
           "continue_orbit", "continue_equilibria", "Branch", "Bifurcation", "EquilibriumBranch",
           "ContinuationError", "continue_bifurcation", "BifurcationCurve", "CodimTwoPoint",
           "shapiro_tongue", "ShapiroTongue", "bifurcation_tree", "BranchTree",
           "wada_test", "WadaTest", "kaplan_yorke_dimension"]

# the pendulum of the classroom in metres, seconds and degrees
__all__ += ["Pendulum", "Swing"]
# the quantum pendulum
__all__ += ["mathieu_a", "mathieu_b", "mathieu_exponent", "mathieu_ce", "mathieu_se", "mathieu_me", "Transmon"]
# networks of pendula
__all__ += ["Network", "NetworkEquilibrium", "NormalModes", "DCSquid", "RFSquid", "fluxon_velocity"]
# the spherical pendulum exactly; the double pendulum's exact parts (normal modes, the forbidden flip region)
from .systems.spherical import SphericalOrbit, SphericalPath, spherical_orbit  # noqa: E402
from .systems.double import DoublePendulumModes, double_pendulum_modes, flip_forbidden  # noqa: E402
# the double pendulum integrated: its path and energy error, the flip-time map, the Lyapunov spectrum
from .systems.double_motion import DoublePendulum, FlipMap, LyapunovSpectrum  # noqa: E402
# the Foucault pendulum: the spherical pendulum in the Earth's frame, its precession split
from .systems.foucault import FoucaultPendulum, FoucaultPrecession  # noqa: E402
# the scene files of those systems (&double, &foucault, &network), read by the kernel as pendula-run reads them
from .systems.scene_files import system_from_namelist  # noqa: E402

__all__ += ["spherical_orbit", "SphericalOrbit", "SphericalPath",
            "double_pendulum_modes", "DoublePendulumModes", "flip_forbidden",
            "DoublePendulum", "FlipMap", "LyapunovSpectrum", "FoucaultPendulum", "FoucaultPrecession",
            "system_from_namelist"]
__all__ += ["thermal_rate", "quantum_rate", "escape_rate", "crossover_temperature", "switching_distribution",
            "SwitchingDistribution", "rf_current"]
