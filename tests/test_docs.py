"""The documentation says what the code does.

* every docstring example of the installed package runs and prints what it says;
* README's Python blocks run as pasted and print the output block that follows them;
* README stays a newcomer's page: short, its links resolve, no history of the work in it.
"""

import contextlib
import doctest
import importlib
import importlib.util
import inspect
import io
import pathlib
import pkgutil
import re

import pytest

import pendula

ROOT = pathlib.Path(__file__).resolve().parents[1]
README = ROOT / "README.md"

# every module of the package except the command-line entry points, whose import runs them
MODULES = sorted(m.name for m in pkgutil.walk_packages(pendula.__path__, "pendula.")
                 if not m.name.endswith("__main__") and not m.name.split(".")[-1].startswith("_"))


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name):
    mod = importlib.import_module(name)
    failures, tried = doctest.testmod(mod, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert failures == 0


def _blocks(text):
    """(language, body) of each fenced block, in order."""
    return [(m.group(1), m.group(2)) for m in re.finditer(r"^```(\w*)\n(.*?)^```", text, re.S | re.M)]


def test_readme_python_blocks_run_and_print_what_follows_them(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    blocks = _blocks(README.read_text())
    ran = 0
    for i, (lang, body) in enumerate(blocks):
        if lang != "python":
            continue
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            exec(compile(body, f"README block {i}", "exec"), {"__name__": "__readme__"})
        ran += 1
        if i + 1 < len(blocks) and blocks[i + 1][0] == "text":
            assert out.getvalue() == blocks[i + 1][1], f"README block {i} prints something else"
    assert ran >= 1


def test_readme_is_short_and_has_no_history_of_the_work():
    text = README.read_text()
    assert len(text.splitlines()) < 200
    for pattern in (r"\bissue\s*\d", r"\bthe seeds?\b", r"\bseed's\b", r"#\d+\b"):
        assert not re.search(pattern, text, re.I), pattern


def test_readme_links_resolve():
    text = README.read_text()
    links = re.findall(r"\]\(([^)#]+)\)", text)
    assert links
    for link in links:
        if "://" in link:
            continue
        assert (ROOT / link).exists(), link


def test_readme_names_only_code_that_exists():
    """Every `pendula.NAME` README mentions is a public name or a public module, and every
    `pendula.MODULE.NAME` a name of that module."""
    text = README.read_text()
    names = set(re.findall(r"pendula\.([A-Za-z_]\w*)", text))
    assert names
    modules = {n for n in names - set(pendula.__all__) if not n.startswith("_")
               and importlib.util.find_spec(f"pendula.{n}") is not None}
    assert names <= set(pendula.__all__) | {"__version__"} | modules, names - set(pendula.__all__) - modules
    for mod, name in re.findall(r"pendula\.([a-z]\w*)\.([A-Za-z_]\w*)", text):
        if mod in modules:
            assert hasattr(importlib.import_module(f"pendula.{mod}"), name), f"pendula.{mod}.{name}"


def test_installed_package_is_marked_typed():
    assert (pathlib.Path(pendula.__file__).parent / "py.typed").exists()


def _sections(doc):
    """The numpydoc section titles of a docstring (a line underlined with dashes)."""
    lines = inspect.cleandoc(doc or "").splitlines()
    return {a.strip() for a, b in zip(lines, lines[1:]) if a.strip() and b.strip() and set(b.strip()) == {"-"}}


def _required(obj):
    need = {"Examples", "See Also"}
    if inspect.isclass(obj):
        if not issubclass(obj, BaseException):
            need.add("Parameters|Attributes")
        return need
    fn = inspect.unwrap(obj)
    if inspect.signature(fn).parameters:
        need.add("Parameters")
    need.add("Returns")
    if re.search(r"^\s+raise\b", inspect.getsource(fn), re.M):
        need.add("Raises")
    return need


@pytest.mark.parametrize("name", sorted(pendula.__all__))
def test_public_name_has_the_numpydoc_sections(name):
    """Parameters, Returns, Raises where it raises, See Also and a runnable Example
    (the examples run in test_docstring_examples)."""
    obj = getattr(pendula, name)
    doc = inspect.getdoc(obj) or ""
    have = _sections(doc)
    missing = [s for s in _required(obj) if not set(s.split("|")) & have]
    assert not missing, f"pendula.{name}: docstring lacks {missing}"
    assert ">>> " in doc, f"pendula.{name}: its Examples section has no doctest"


DOCS = ROOT / "docs" / "source"


def test_every_figure_function_is_in_the_api_reference_with_its_numpydoc_sections():
    """pendula.plot's public functions (its __all__, each defined) are listed on the API page and
    carry Parameters, Returns and a runnable example, as the package's own names do."""
    import pendula.plot as pp

    listed = set(re.findall(r"^   (\w+)$", (DOCS / "api.rst").read_text().split(".. currentmodule:: pendula.plot")[1],
                            re.M))
    assert set(pp.__all__) <= listed, sorted(set(pp.__all__) - listed)
    for name in pp.__all__:
        doc = inspect.getdoc(getattr(pp, name)) or ""
        assert {"Parameters", "Returns"} <= _sections(doc) and ">>> " in doc, f"pendula.plot.{name}"


def _page_blocks(path):
    """The Python code blocks of a page: Markdown fences and reST code-block directives."""
    text = path.read_text()
    blocks = re.findall(r"^```python\n(.*?)^```", text, re.S | re.M)
    for m in re.finditer(r"^\.\. code-block:: python\n\n((?:   .*\n|\n)+)", text, re.M):
        blocks.append("\n".join(line[3:] for line in m.group(1).splitlines()))
    return blocks


PAGES_WITH_CODE = sorted(str(p.relative_to(DOCS)) for p in list(DOCS.rglob("*.md")) + list(DOCS.rglob("*.rst"))
                         if not {"gallery", "generated", "_build"} & set(p.parts) and _page_blocks(p))


@pytest.mark.parametrize("page", PAGES_WITH_CODE)
def test_python_blocks_of_the_docs_pages_run(page, tmp_path, monkeypatch):
    """Every Python block of a page runs as pasted (the blocks of a page share one namespace)."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "agg")
    ns = {"__name__": "__docs__"}
    with contextlib.redirect_stdout(io.StringIO()):
        for i, block in enumerate(_page_blocks(DOCS / page)):
            exec(compile(block, f"{page} block {i}", "exec"), ns)
