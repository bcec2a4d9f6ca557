"""Sphinx configuration of pendula's documentation site.

The build never touches the network: intersphinx reads small inventories stored
in ``docs/inventories`` (written by ``docs/make_inventories.py``), and the
toctrees of each section are written here from the pages that exist, so pages
added by other work (``install``, ``license``, ``bad_input``, ``sweeps_at_scale``,
``work_precision``, ``accuracy*``) join their section when present and nothing
breaks when they are absent.
"""

from __future__ import annotations

import os
import pathlib
import sys
import warnings

HERE = pathlib.Path(__file__).resolve().parent
DOCS = HERE.parent
ROOT = DOCS.parent

import pendula  # noqa: E402  (the installed package: the API reference documents what users get)

project = "pendula"
author = "the pendula authors"
copyright = "the pendula authors; GPL-3.0-or-later"
release = version = pendula.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "myst_parser",
    "matplotlib.sphinxext.plot_directive",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "_toc", "_api_generated.rst", "**.ipynb_checkpoints"]
templates_path = ["_templates"]
myst_heading_anchors = 3
suppress_warnings = ["myst.header"]

# ---- API reference ---------------------------------------------------------
autosummary_generate = ["api.rst", "_api_generated.rst"]
autosummary_imported_members = True
autodoc_typehints = "none"          # numpydoc's Parameters section carries the types
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
# numpydoc links a class's properties from its Attributes section; the class pages
# document the fields in that section and do not repeat them as members
nitpick_ignore = [("py:obj", "amplitude"), ("py:obj", "kind"), ("py:obj", "stable")]

# ---- intersphinx: local inventories only (no network in the build) --------
_INV = DOCS / "inventories"
intersphinx_mapping = {
    name: (url, str(_INV / f"{name}.inv"))
    for name, url in {
        "python": "https://docs.python.org/3/",
        "numpy": "https://numpy.org/doc/stable/",
        "scipy": "https://docs.scipy.org/doc/scipy/",
        "xarray": "https://docs.xarray.dev/en/stable/",
        "matplotlib": "https://matplotlib.org/stable/",
    }.items()
    if (_INV / f"{name}.inv").exists()
}
intersphinx_timeout = 1

# ---- sphinx-gallery ----------------------------------------------------------
os.environ.setdefault("MPLBACKEND", "agg")
warnings.filterwarnings("ignore", message="Matplotlib is currently using agg")
sphinx_gallery_conf = {
    "examples_dirs": str(DOCS / "examples"),
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",
    "matplotlib_animations": (True, "jshtml"),
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "show_memory": False,
    "abort_on_example_error": True,
    "write_computation_times": False,
}

# ---- figures drawn by the code shown beside them (the getting-started tutorial, the guide) ----
plot_include_source = True
plot_html_show_source_link = False
plot_html_show_formats = False
plot_formats = [("png", 96)]
plot_pre_code = "import numpy as np\nimport matplotlib.pyplot as plt\n"
plot_rcparams = {"font.size": 9}

# No page may load anything from the network (the site must work offline, and
# the browser check fails on any resource that does not load): no MathJax
# (formulas are written in Unicode: a :math: role or a math directive would make
# Sphinx load MathJax from its CDN), no CDN scripts.

# ---- HTML ------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = "pendula"
html_static_path = ["_static"]
html_favicon = "_static/pendula.svg"
html_logo = "_static/pendula.svg"
html_context = {"default_mode": "light"}
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 7,
    "use_edit_page_button": False,
}
html_show_sourcelink = False
html_last_updated_fmt = None

# ---- section toctrees from the pages that exist -----------------------------
#: each section: (toc file, caption, pages in order).  A name ending in '*'
#: takes every top-level page whose name starts with it.
SECTIONS = {
    "getting_started": ["install*"],
    "guide": ["guide/exact", "guide/integrators", "guide/effects", "guide/spectra", "guide/damping",
              "guide/josephson", "guide/driven",
              "guide/cord", "guide/cycloid", "guide/gravity", "guide/density", "guide/dynamics", "guide/attractors",
              "guide/continuation",
              "guide/quantum",
              "guide/circuits",
              "guide/spherical", "guide/double",
              "guide/sweeps",
              "sweeps_at_scale*", "guide/scenes"],
    "reports": ["reports/accuracy", "accuracy*", "elliptic_edges*", "model_accuracy*", "reports/cost", "work_precision*", "reports/benchmarks",
                "reports/limits"],
    "about": ["bad_input*", "slips", "changelog", "license*"],
    # how pendula is built and checked: for those who change it, apart from the user's guide
    "developer": ["guide/architecture", "scenes*", "vocabulary", "develop"],
}
# the classroom pendulum (metres, seconds, degrees) right after the exact pendulum
SECTIONS["guide"].insert(SECTIONS["guide"].index("guide/exact") + 1, "guide/laboratory")


def _existing(pattern: str, taken: set[str]) -> list[str]:
    if pattern.endswith("*"):
        stem = pattern[:-1]
        names = sorted({p.stem for p in HERE.glob(stem + "*") if p.suffix in (".rst", ".md")})
        return [n for n in names if n not in taken]
    return [pattern] if any((HERE / (pattern + s)).exists() for s in (".rst", ".md")) else []


def _write_tocs() -> None:
    toc = HERE / "_toc"
    toc.mkdir(exist_ok=True)
    taken: set[str] = set()
    for name, patterns in SECTIONS.items():
        entries = []
        for pat in patterns:
            for doc in _existing(pat, taken):
                taken.add(doc)
                entries.append(doc)
        # toctree entries are relative to the page that includes the file, i.e. the section page
        text = ".. toctree::\n   :maxdepth: 2\n\n" + "".join(f"   /{e}\n" for e in entries)
        path = toc / f"{name}.rst.inc"
        if not path.exists() or path.read_text() != text:
            path.write_text(text)
    # top-level pages nobody placed (written elsewhere and new to this list): an 'other' section
    known = taken | {"index", "api", "getting_started", "about", "developer"}
    rest = sorted({p.stem for p in HERE.iterdir() if p.suffix in (".rst", ".md") and not p.stem.startswith("_")} - known)
    text = (".. toctree::\n   :maxdepth: 1\n\n" + "".join(f"   /{e}\n" for e in rest)) if rest else ""
    path = toc / "other.rst.inc"
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


_write_tocs()

# ---- the API reference: every name of pendula.__all__, grouped --------------
API_GROUPS = [
    ("Elliptic functions", ["ellipk", "ellipe", "ellipf", "ellipeinc", "ellipj", "nome"]),
    ("Scenes and simulation", ["Scene", "SceneError", "simulate", "Trajectory", "models", "ModelInfo",
                               "capabilities", "Capability", "time_scales", "TimeScales"]),
    ("The exact pendulum", ["orbit", "Orbit", "exact_motion", "period", "energy"]),
    ("Series", ["period_series", "period_from_series", "poincare_lindstedt"]),
    ("Events", ["find_events", "numerical_period", "Events"]),
    ("Spectra", ["spectrum", "spectra", "Spectrum", "fourier_series", "FourierSeries", "odd_harmonics_above",
                 "precompute_wisdom", "wisdom_path"]),
    ("The flexible cord", ["flip_map", "cord_state", "flip_sequence"]),
    ("Huygens' cycloid and non-uniform gravity", ["cycloid_geometry", "cycloid_period", "CycloidGeometry",
                                                  "gravity_orbit"]),
    ("The density of the angle", ["angle_density", "angle_cdf", "arcsine_density"]),
    ("Sweeps", ["sweep", "iv_curve"]),
    ("Equilibria, periodic orbits and attractors", ["equilibria", "Equilibrium", "periodic_orbit",
                                                    "PeriodicOrbit", "attractor_map",
                                                    "attractor_continuation", "wada_test", "WadaTest",
                                                    "kaplan_yorke_dimension"]),
    ("Continuation and bifurcations", ["continue_orbit", "Branch", "Bifurcation", "bifurcation_tree", "BranchTree",
                                       "continue_equilibria", "EquilibriumBranch", "ContinuationError",
                                       "continue_bifurcation", "BifurcationCurve", "CodimTwoPoint", "shapiro_tongue",
                                       "ShapiroTongue"]),
    ("The Josephson junction", ["Junction", "SwitchingCurrents"]),
    ("The quantum pendulum", ["Transmon", "mathieu_a", "mathieu_b", "mathieu_exponent", "mathieu_ce", "mathieu_se",
                              "mathieu_me"]),
    ("Circuits and chains", ["Network", "NetworkEquilibrium", "NormalModes", "network_time_scales",
                             "NetworkTimeScales", "DCSquid", "RFSquid", "fluxon_velocity"]),
    ("The spherical and the double pendulum", ["spherical_orbit", "SphericalOrbit", "SphericalPath",
                                               "double_pendulum_modes", "DoublePendulumModes", "flip_forbidden",
                                               "DoublePendulum", "FlipMap", "LyapunovSpectrum",
                                               "FoucaultPendulum", "FoucaultPrecession",
                                               "system_from_namelist"]),
    ("Escape, switching at any ramp rate, rf", ["escape_rate", "thermal_rate", "quantum_rate",
                                                "crossover_temperature", "switching_distribution",
                                                "SwitchingDistribution", "rf_current"]),
]
# the pendulum of the classroom (metres, seconds, degrees)
API_GROUPS += [("The pendulum in laboratory units", ["Pendulum", "Swing"])]


def _write_api() -> None:
    public = list(pendula.__all__)
    out = [".. currentmodule:: pendula", ""]
    placed = set()
    for title, names in API_GROUPS + [("Other", [n for n in public if n not in
                                                 {x for _, g in API_GROUPS for x in g}])]:
        names = [n for n in names if n in public]
        if not names:
            continue
        placed.update(names)
        out += [title, "-" * len(title), "", ".. autosummary::", "   :toctree: generated", ""]
        out += [f"   {n}" for n in names] + [""]
    path = HERE / "_api_generated.rst"
    text = "\n".join(out) + "\n"
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


_write_api()


# ---- animations without the network ------------------------------------------
# matplotlib's HTML player links Font Awesome 4 from a CDN for its button icons;
# the PyData theme already ships Font Awesome (whose 'fa fa-play' ... names still
# work), so the link is dropped from the player matplotlib writes (the gallery's
# scripts run in this process).
def _offline_animation_player() -> None:
    import matplotlib.animation as animation

    link = ('<link rel="stylesheet"\n'
            'href="https://maxcdn.bootstrapcdn.com/font-awesome/4.4.0/css/font-awesome.min.css">')
    if link in animation.JS_INCLUDE:
        animation.JS_INCLUDE = animation.JS_INCLUDE.replace(link, "")


_offline_animation_player()


# ---- figures carry their smallest text size (pixels) for the browser check ----
# docs/tools/figure_text.py: every PNG the build writes gets a text chunk
# 'pendula-min-text-px'; tests/docs_browser_check.py fails a figure shown with
# text under 9 px
sys.path.insert(0, str(DOCS / "tools"))
import figure_text  # noqa: E402

figure_text.install()

# ---- code blocks wrap within the column (docs/source/_static/pendula.css) ----
html_css_files = ["pendula.css"]
