"""The Python package's imports run one way: no module imports one above it.

Walks every module of python/pendula with ast (imports at any depth, inside
functions too) and fails on a circle in the import graph, naming it.
"""

import ast
import pathlib

import pytest

PKG = pathlib.Path(__file__).resolve().parents[1] / "python" / "pendula"


def _module_name(path: pathlib.Path) -> str:
    rel = path.relative_to(PKG.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _graph() -> dict[str, set[str]]:
    mods = {_module_name(p): p for p in PKG.rglob("*.py")}
    mods["pendula._kernel"] = None  # the compiled extension: a leaf
    graph = {m: set() for m in mods}
    for name, path in mods.items():
        if path is None:
            continue
        is_pkg = path.name == "__init__.py"
        base = name.split(".") if is_pkg else name.split(".")[:-1]
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            targets = []
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    root = base[: len(base) - (node.level - 1)]
                    mod = ".".join(root + ([node.module] if node.module else []))
                else:
                    mod = node.module or ""
                # 'from pkg import name': an edge to the submodule pkg.name when it is
                # one, otherwise to pkg itself (the name comes from its __init__)
                for a in node.names:
                    targets.append(f"{mod}.{a.name}" if f"{mod}.{a.name}" in mods else mod)
            elif isinstance(node, ast.Import):
                targets += [a.name for a in node.names]
            for tgt in targets:
                if tgt in mods and tgt != name:
                    graph[name].add(tgt)
    # a package's __init__ is imported by each of its submodules' import: that edge is Python's, not ours
    return graph


def _cycle(graph):
    state, stack = {}, []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for m in sorted(graph[n]):
            if state.get(m) == 1:
                return stack[stack.index(m):] + [m]
            if m not in state:
                found = visit(m)
                if found:
                    return found
        stack.pop()
        state[n] = 2
        return None

    for n in sorted(graph):
        if n not in state:
            found = visit(n)
            if found:
                return found
    return None


def test_graph_sees_the_package():
    g = _graph()
    assert "pendula.motion" in g and "pendula.systems" in g["pendula.motion"]


def test_no_import_circle():
    cyc = _cycle(_graph())
    assert cyc is None, "import circle: " + " -> ".join(cyc)


@pytest.mark.parametrize("low", ["pendula.elliptic", "pendula.series", "pendula.scene", "pendula.trajectory",
                                 "pendula.systems.rigid", "pendula._checks", "pendula._files",
                                 "pendula.quantum", "pendula.mathieu_floquet", "pendula.systems.network",
                                 "pendula.systems.spherical", "pendula.systems.double", "pendula.systems.double_motion", "pendula.systems.double_sweep",
                                 "pendula.systems.foucault",
                                 # the junction's layer (with junction.py): escape, the RSJ junction, rf
                                 "pendula.escape", "pendula.overdamped", "pendula.rf",
                                 # the SQUIDs on the network and the junction
                                 "pendula.squid", "pendula.squid_voltage", "pendula.squid_sweep", "pendula.rf_squid", "pendula.long_junction",
                                 "pendula.junction_lab", "pendula.junction_switching"])
def test_lower_layers_do_not_import_the_user_facing_ones(low):
    top = {"pendula", "pendula.motion", "pendula.run", "pendula.cli", "pendula.plot", "pendula.studies", "pendula.studies.accuracy", "pendula.studies.bench", "pendula.studies.workprecision"}
    # the classroom pendulum and the animation writer sit beside pendula.motion and pendula.plot
    top |= {"pendula.laboratory", "pendula.animation", "pendula.studies.explained", "pendula.studies.workprecision_report",
            "pendula.run_figures", "pendula._plot_common", "pendula._plot_systems"}
    g = _graph()
    seen, todo = set(), [low]
    while todo:
        n = todo.pop()
        for m in g.get(n, ()):
            if m not in seen:
                seen.add(m)
                todo.append(m)
    assert not (seen & top), f"{low} reaches {sorted(seen & top)}"


def test_modules_do_not_import_from_the_package_front():
    """pendula/__init__ re-exports the public names; modules inside import from
    where a name is defined, never from the front (that would be upward)."""
    g = _graph()
    bad = sorted(n for n, deps in g.items() if "pendula" in deps and n != "pendula")
    assert not bad, f"import from pendula/__init__ inside the package: {bad}"


def test_the_library_does_not_import_its_measuring_apparatus():
    """pendula.studies measures the library; only the command line reaches it, never a library module."""
    g = _graph()
    bad = sorted(n for n, deps in g.items()
                 if not n.startswith("pendula.studies") and n != "pendula.cli"
                 and any(d.startswith("pendula.studies") for d in deps))
    assert not bad, f"library modules importing pendula.studies: {bad}"


def test_dynamics_is_one_subpackage():
    g = _graph()
    for name in ("pendula.dynamics.equilibria", "pendula.dynamics.periodic", "pendula.dynamics.attractors"):
        assert name in g, f"{name} is not a module of the package"


def test_the_junction_modules_sit_beside_the_junction():
    """escape builds on junction (its constants and Junction); junction runs the overdamped junction through
    overdamped; neither overdamped nor rf imports junction (no circle)."""
    g = _graph()
    assert "pendula.junction" in g["pendula.escape"]
    assert "pendula.overdamped" in g["pendula.junction"]
    assert "pendula.junction" not in g["pendula.overdamped"] and "pendula.junction" not in g["pendula.rf"]
