"""Open every page of the built documentation site in headless Chromium.

    python tests/docs_browser_check.py docs/_build/html [--screenshots DIR]

Serves the folder over HTTP on a free local port, then, through selenium and
Debian's chromium + chromium-driver, checks on every page: it loads, the
browser console holds no error, every image has loaded (a natural width > 0),
every animation of the gallery has its player and its first frame, the page
has a title (an ``h1`` with text in the main column), no table sticks out of
the main column (a table may scroll inside its own container), no code block
scrolls sideways (code, output, listings and doctest examples alike must fit
the column), and no figure's text is shown smaller than 9 px: each PNG the
docs build writes carries its smallest text size in pixels
(docs/tools/figure_text.py), which is scaled by the width the page shows the
image at; figures without that record (committed images) are counted as
unmeasured.  Then the search page must find ``ellipj``.  Exits 1 naming each failure; 0 when all
pass.  (Not a pytest module: ``make docs-check`` runs it after ``make docs``.)
"""

from __future__ import annotations

import argparse
import functools
import http.server
import pathlib
import sys
import threading
import time
import urllib.parse

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"


def serve(root: pathlib.Path):
    handler = functools.partial(http.server.SimpleHTTPRequestHandler, directory=str(root))

    class Quiet(handler.func):
        def log_message(self, *args):
            pass

    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=str(root)))
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    return httpd, f"http://127.0.0.1:{httpd.server_address[1]}/"


def browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
              "--window-size=1400,1000"):
        opts.add_argument(a)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(CHROMEDRIVER), options=opts)


IMAGES_JS = """
const bad = [];
for (const img of document.images) {
  if (!img.complete || img.naturalWidth === 0) bad.push(img.getAttribute('src').slice(0, 120));
}
return bad;
"""

ANIMATIONS_JS = """
const players = document.querySelectorAll('div.animation');
const out = [];
for (const p of players) {
  const img = p.querySelector('img');
  out.push(img !== null && img.complete && img.naturalWidth > 0);
}
return out;
"""


LAYOUT_JS = """
const main = document.querySelector('article.bd-article') || document.querySelector('main') || document.body;
const box = main.getBoundingClientRect();
const h1 = main.querySelector('h1');
const out = {title: !!(h1 && h1.textContent.trim()), overflow: []};
const scroller = el => {
  for (let e = el.parentElement; e && e !== main; e = e.parentElement) {
    const s = getComputedStyle(e).overflowX;
    if ((s === 'auto' || s === 'scroll') && e.getBoundingClientRect().right <= box.right + 1) return e;
  }
  return null;
};
for (const t of main.querySelectorAll('table')) {
  if (t.getBoundingClientRect().right > box.right + 1 && !scroller(t))
    out.overflow.push('table "' + t.textContent.trim().replace(/\\s+/g, ' ').slice(0, 60) + '"');
}
// every code block fits the column: none sticks out, none scrolls sideways
for (const p of main.querySelectorAll('div.highlight pre')) {
  if (p.getBoundingClientRect().right > box.right + 1 || p.scrollWidth > p.clientWidth + 1)
    out.overflow.push('code block "' + p.textContent.trim().split('\\n')[0].slice(0, 60) + '"');
}
return out;
"""


# the PNG figures of the main column as shown: their address, shown width and natural width
# (gallery thumbnails are previews, and the animation players' frames are inline data: both skipped)
FIGURES_JS = """
const main = document.querySelector('article.bd-article') || document.querySelector('main') || document.body;
const out = [];
for (const img of main.querySelectorAll('img')) {
  if (img.closest('.sphx-glr-thumbcontainer')) continue;
  const src = img.currentSrc || img.src;
  if (!/^https?:.*[.]png([?#]|$)/i.test(src)) continue;
  out.push({src: src, shown: img.getBoundingClientRect().width, natural: img.naturalWidth});
}
return out;
"""

#: the smallest text a figure may show, CSS pixels
MIN_TEXT_PX = 9.0
#: the PNG text chunk docs/tools/figure_text.py writes
TEXT_KEY = "pendula-min-text-px"


def png_min_text_px(path: pathlib.Path) -> float | None:
    """The smallest text size a PNG records (pixels of the image), None when it records none."""
    from PIL import Image

    try:
        with Image.open(path) as im:
            value = getattr(im, "text", {}).get(TEXT_KEY) or im.info.get(TEXT_KEY)
    except OSError:
        return None
    return float(value) if value else None


def figure_failures(page: str, figures: list[dict], site: pathlib.Path) -> tuple[list[str], int]:
    """(failures, unmeasured): each figure whose smallest text, scaled to the width it is shown at, is
    under MIN_TEXT_PX; and how many figures record no text size."""
    failures, unmeasured = [], 0
    for f in figures:
        if not (f["shown"] > 0 and f["natural"] > 0):   # hidden, or not loaded (reported by IMAGES_JS)
            continue
        rel = urllib.parse.unquote(urllib.parse.urlsplit(f["src"]).path).lstrip("/")
        px = png_min_text_px(site / rel)
        if px is None:
            unmeasured += 1
            continue
        shown = px * f["shown"] / f["natural"]
        if shown < MIN_TEXT_PX:
            failures.append(f"{page}: figure {rel}: its smallest text is {shown:.1f} px as shown "
                            f"({px:.1f} px in the image, shown at {f['shown']:.0f} of {f['natural']} px wide); "
                            f"at least {MIN_TEXT_PX:g} px")
    return failures, unmeasured


def layout_failures(page: str, layout: dict) -> list[str]:
    """The failures of one page's layout: no title, or tables and code blocks wider than the column."""
    out = [] if layout["title"] else [f"{page}: no title (no h1 in the main column)"]
    return out + [f"{page}: wider than the main column: {what}" for what in layout["overflow"]]


def wait_loaded(driver, timeout=20.0):
    t0 = time.time()
    while time.time() - t0 < timeout:
        if driver.execute_script("return document.readyState") == "complete":
            return True
        time.sleep(0.05)
    return False


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("site", type=pathlib.Path)
    ap.add_argument("--screenshots", type=pathlib.Path, default=None,
                    help="save a screenshot of each page into this folder")
    args = ap.parse_args(argv)
    site = args.site.resolve()
    pages = sorted(p.relative_to(site).as_posix() for p in site.rglob("*.html")
                   if not p.relative_to(site).parts[0].startswith("_"))
    if "index.html" not in pages:
        print(f"docs browser check: no index.html in {site}: build the site first (make docs)")
        return 1
    httpd, base = serve(site)
    driver = browser()
    failures = []
    n_images = n_animations = n_unmeasured = 0
    try:
        for page in pages:
            driver.get(base + page)
            if not wait_loaded(driver):
                failures.append(f"{page}: did not finish loading")
                continue
            time.sleep(0.05)
            for entry in driver.get_log("browser"):
                if entry["level"] == "SEVERE":
                    failures.append(f"{page}: console error: {entry['message'][:300]}")
            bad = driver.execute_script(IMAGES_JS)
            n_images += driver.execute_script("return document.images.length")
            failures += [f"{page}: image not loaded: {src}" for src in bad]
            failures += layout_failures(page, driver.execute_script(LAYOUT_JS))
            small, unmeasured = figure_failures(page, driver.execute_script(FIGURES_JS), site)
            failures += small
            n_unmeasured += unmeasured
            anim = driver.execute_script(ANIMATIONS_JS)
            n_animations += len(anim)
            failures += [f"{page}: animation {i} has no frame" for i, ok in enumerate(anim) if not ok]
            if args.screenshots:
                args.screenshots.mkdir(parents=True, exist_ok=True)
                driver.save_screenshot(str(args.screenshots / (page.replace("/", "__") + ".png")))
        # the search page finds ellipj (the index is loaded and searched by the page's own script)
        driver.get(base + "search.html?q=ellipj")
        found = []
        t0 = time.time()
        while time.time() - t0 < 20 and not found:
            time.sleep(0.2)
            found = driver.execute_script(
                "return Array.from(document.querySelectorAll('#search-results li a'))"
                ".map(a => a.getAttribute('href'));")
        for entry in driver.get_log("browser"):
            if entry["level"] == "SEVERE":
                failures.append(f"search.html?q=ellipj: console error: {entry['message'][:300]}")
        if not any("ellipj" in (h or "") for h in found):
            failures.append(f"search for 'ellipj' found no page about it (results: {found[:5]})")
    finally:
        driver.quit()
        httpd.shutdown()
    print(f"docs browser check: {len(pages)} pages, {n_images} images ({n_unmeasured} figures without a "
          f"recorded text size), {n_animations} animations, search for 'ellipj': {len(found)} results")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
