"""Open every page of the built documentation site in headless Chromium.

    python tests/docs_browser_check.py docs/_build/html [--screenshots DIR]

Serves the folder over HTTP on a free local port, then, through selenium and
Debian's chromium + chromium-driver, checks on every page: it loads, the
browser console holds no error, every image has loaded (a natural width > 0),
every animation of the gallery has its player and its first frame, the page
has a title (an ``h1`` with text in the main column), and no table or code
block sticks out of the main column: a table may scroll inside its own
container; code a reader copies must fit (no horizontal scroll bar), while
printed output, plain listings and the API reference's doctest examples may
scroll inside their block.  Then the search
page must find ``ellipj``.  Exits 1 naming each failure; 0 when all
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
// code a reader copies must fit the column; printed output, plain listings and the API
// reference's doctest examples (written to the code's line length) may scroll inside their block
const mayScroll = p => p.closest('.sphx-glr-script-out, .highlight-text, .highlight-none, .highlight-default')
  || location.pathname.includes('/generated/');
for (const p of main.querySelectorAll('div.highlight pre')) {
  if (p.getBoundingClientRect().right > box.right + 1 || (p.scrollWidth > p.clientWidth + 1 && !mayScroll(p)))
    out.overflow.push('code block "' + p.textContent.trim().split('\\n')[0].slice(0, 60) + '"');
}
return out;
"""


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
    n_images = n_animations = 0
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
    print(f"docs browser check: {len(pages)} pages, {n_images} images, {n_animations} animations, "
          f"search for 'ellipj': {len(found)} results")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
