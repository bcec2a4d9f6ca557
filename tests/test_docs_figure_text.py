"""The documentation's figure-text record and the browser check's reading of it, without a browser.

docs/tools/figure_text.py writes each PNG's smallest text size (pixels) into
the file; tests/docs_browser_check.py scales it by the width a page shows the
image at and fails under 9 px.  Here a figure is saved with known font sizes
and dpi, and the check's arithmetic is run on made-up widths.
"""

import importlib.util
import pathlib
import sys

import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
pytest.importorskip("PIL")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _load(name, path):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


figure_text = _load("figure_text", ROOT / "docs" / "tools" / "figure_text.py")
check = _load("docs_browser_check", ROOT / "tests" / "docs_browser_check.py")


@pytest.fixture(autouse=True)
def _installed():
    plain = matplotlib.figure.Figure.savefig
    figure_text.install()
    yield
    matplotlib.figure.Figure.savefig = plain
    plt.close("all")


def test_png_records_its_smallest_text_in_pixels(tmp_path):
    fig, ax = plt.subplots(figsize=(4, 3))
    ax.plot([0, 1], [0, 1])
    ax.set_xlabel("t (s)", fontsize=12)
    ax.tick_params(labelsize=6)                      # the smallest text: 6 pt tick labels
    fig.savefig(tmp_path / "a.png", dpi=96)
    assert check.png_min_text_px(tmp_path / "a.png") == pytest.approx(6 * 96 / 72, abs=1e-3)


def test_dpi_figure_and_other_formats(tmp_path):
    fig, ax = plt.subplots(figsize=(2, 2), dpi=50)
    ax.set_title("x", fontsize=10)
    ax.tick_params(labelsize=10)
    fig.savefig(tmp_path / "b.png", dpi="figure")
    assert check.png_min_text_px(tmp_path / "b.png") == pytest.approx(10 * 50 / 72, abs=1e-3)
    fig.savefig(tmp_path / "b.svg")                  # not a PNG: written as before
    assert (tmp_path / "b.svg").read_text().lstrip().startswith("<?xml")


def test_browser_check_fails_a_figure_shrunk_below_9px(tmp_path):
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.tick_params(labelsize=9)
    ax.xaxis.label.set_fontsize(9)
    ax.yaxis.label.set_fontsize(9)
    fig.savefig(tmp_path / "c.png", dpi=96)            # 12 px text in an image 768 px wide
    src = "http://127.0.0.1:8000/c.png"
    ok, unmeasured = check.figure_failures("p.html", [{"src": src, "shown": 768, "natural": 768}], tmp_path)
    assert ok == [] and unmeasured == 0
    small, _ = check.figure_failures("p.html", [{"src": src, "shown": 400, "natural": 768}], tmp_path)
    assert len(small) == 1 and "6.2 px as shown" in small[0]      # 12 x 400 / 768


def test_an_image_without_the_record_is_counted_unmeasured(tmp_path):
    from PIL import Image

    Image.new("RGB", (10, 10)).save(tmp_path / "plain.png")
    fails, unmeasured = check.figure_failures(
        "p.html", [{"src": "http://h/plain.png", "shown": 10, "natural": 10}], tmp_path)
    assert fails == [] and unmeasured == 1
