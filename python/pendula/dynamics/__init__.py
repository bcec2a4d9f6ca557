"""The dynamics of the pendulum models: equilibria, periodic orbits, attractors.

- :mod:`.equilibria`: the rest points of an autonomous scene and their linear stability;
- :mod:`.periodic`: periodic orbits of a driven scene, by Newton on the stroboscopic
  map with its monodromy (the Floquet multipliers); the one Newton/monodromy core
  the rest of this package builds on;
- :mod:`.continuation`: periodic orbits followed in a parameter, with their bifurcations (on the
  same core; the records in :mod:`.branches`, the homoclinic end in :mod:`.homoclinic`, every branch
  born on a branch in :mod:`.branch_tree`), and
  :mod:`.equilibrium_continuation` the rest points followed likewise; :mod:`.bifurcation_curves`
  follows a fold or a period doubling in two fields, :mod:`.tongues` the Shapiro steps' edges as such curves;
- :mod:`.attractors`: the attractors of the stroboscopic map and their basins (the records and the
  measures of a basin map); :mod:`.attractor_maps` computes the maps (on the sweep engine),
  :mod:`.attractor_continuation` follows them over a parameter, :mod:`.boundary_measures` tests
  their boundaries for the Wada property.

The public names are importable from :mod:`pendula` as well.
"""

from .attractors import Attractor, AttractorMap
from .attractor_maps import attractor_map
from .attractor_continuation import attractor_continuation
from .bifurcation_curves import BifurcationCurve, CodimTwoPoint, continue_bifurcation
from .attractors import kaplan_yorke_dimension
from .boundary_measures import WadaTest, wada_test
from .branches import BIFURCATION_KINDS, Bifurcation, Branch, ContinuationError
from .continuation import continue_orbit
from .branch_tree import BranchTree, bifurcation_tree
from .equilibrium_continuation import EquilibriumBranch, continue_equilibria
from .equilibria import EQUILIBRIUM_KINDS, Equilibrium, equilibria
from .periodic import PeriodicOrbit, periodic_orbit
from .tongues import ShapiroTongue, shapiro_tongue

__all__ = ["Equilibrium", "equilibria", "EQUILIBRIUM_KINDS", "PeriodicOrbit", "periodic_orbit",
           "Attractor", "AttractorMap", "continue_orbit", "continue_equilibria", "Branch", "Bifurcation",
           "EquilibriumBranch", "ContinuationError", "BIFURCATION_KINDS", "attractor_map", "attractor_continuation",
           "continue_bifurcation", "BifurcationCurve", "CodimTwoPoint", "shapiro_tongue", "ShapiroTongue",
           "BranchTree", "bifurcation_tree",
           "wada_test", "WadaTest", "kaplan_yorke_dimension"]
