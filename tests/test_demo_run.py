"""``pendula demo`` run whole, as ``make demo`` runs it: it exits 0, prints its explained summary and
writes every figure it names.  The unit tests of the demo feed its printing functions small results;
this one is the only run of the whole job, so an import or a figure broken anywhere in it (a moved
private helper, a renamed field) fails here.  It takes about a minute: ``make test-full``."""

import os
import subprocess
import sys

import pytest


def test_the_whole_demo_runs_and_writes_its_figures(tmp_path):
    pytest.importorskip("matplotlib")
    pytest.importorskip("xarray")
    pytest.importorskip("tqdm")
    pytest.importorskip("scipy")
    out = tmp_path / "out"
    env = dict(os.environ, MPLBACKEND="Agg")
    run = subprocess.run([sys.executable, "-m", "pendula", "demo", "-q", "-o", str(out)], cwd=tmp_path,
                         env=env, capture_output=True, text=True, timeout=1800, stdin=subprocess.DEVNULL)
    assert run.returncode == 0, run.stderr[-3000:]
    assert "Traceback" not in run.stderr
    text = run.stdout
    # the summary: the elliptic table's verdict, the gallery, the cost of accuracy, the closing count
    assert "elliptic functions:" in text and "eps" in text
    assert "what accuracy costs in time" in text
    assert "gallery files, the integrator study and the sweeps written to" in text
    figures = sorted(out.rglob("*.png"))
    assert len(figures) >= 20, [p.name for p in figures]
    empty = [p.name for p in figures if p.stat().st_size < 2000]
    assert not empty, f"empty or truncated figures: {empty}"
    assert (out / "work_precision.json").is_file()
    assert any((out / "sweeps").iterdir())
