"""dpend explore in a real browser (Debian's chromium, headless, driven by Playwright):
the page on three small maps made here (a flip map, MEGNO over m2/m1 and l2/l1, the
elastic pendulum's MEGNO), checked against the maps' HDF5 files read by h5py.

For each map: hover a pixel and read its value, click it, and check that the run's
value equals the file's to the bit; that the animation advances (two snapshots of
the pendulum's canvas differ); that a shift-clicked neighbour draws the separation
plot; that the browser's console holds no error. Then the keyboard alone, the page's
state in its URL, the downloads, and hostile values refused in one line on the page
and in the server's log. Screenshots go to $DPEND_SCREENSHOTS (CI: out/ci/explore),
else to pytest's tmp_path.
"""
from __future__ import annotations

import csv
import io
import math
import os
import shutil
import time
import urllib.error
import urllib.request

import h5py
import numpy as np
import pytest

import dpend
from dpend.explore._map import open_map
from dpend.explore._server import Explorer, serve_in_thread

CHROMIUM = os.environ.get("DPEND_CHROMIUM", "/usr/bin/chromium")
MUST_RUN = os.environ.get("DPEND_TEST_NO_SKIP") == "1"

# the maps: (name, sweep options, the map the test reads)
MAPS = {
    "flip": (dict(n=24, t_end=20, dt=0.01), "t_flip"),
    "megno_mass_length": (dict(axis1="m2/m1", axis2="l2/l1", n=16, min1=0.1, max1=4,
                               min2=0.1, max2=4, q1=0, q2=0, t_end=20, dt=0.01,
                               indicator="megno"), "megno"),
    "elastic": (dict(model="elastic", k=29.4, l0=1, m=1, g=9.8, q=[1.2, -1.5707963267948966],
                     w=[0, 0], axis1="r", axis2="phi", n=12, min1=0.8, max1=2, min2=-2.8,
                     max2=-0.35, t_end=20, dt=0.01, indicator="megno"), "megno"),
}


def _missing(reason: str):
    if MUST_RUN:
        pytest.fail(f"{reason} (CI runs the browser test: scripts/setup.sh installs "
                    "chromium, python_package.sh playwright)")
    pytest.skip(reason)


@pytest.fixture(scope="module")
def browser():
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        _missing("playwright is not installed (pip install playwright)")
    if not (os.path.exists(CHROMIUM) or shutil.which(CHROMIUM)):
        _missing(f"no chromium at {CHROMIUM} (apt-get install chromium)")
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM,
                              args=["--no-sandbox", "--disable-gpu"])
        yield b
        b.close()


@pytest.fixture(scope="module")
def shots(tmp_path_factory):
    where = os.environ.get("DPEND_SCREENSHOTS")
    path = where or str(tmp_path_factory.mktemp("screenshots"))
    os.makedirs(path, exist_ok=True)
    return path


@pytest.fixture(scope="module")
def maps(tmp_path_factory):
    folder = tmp_path_factory.mktemp("maps")
    out = {}
    for name, (options, _) in MAPS.items():
        path = str(folder / f"{name}.h5")
        dpend.sweep(progress=None, **options).dpend.to_hdf5(path)
        out[name] = path
    return out


class Page:
    """The page of one map in a fresh browser tab, its console and the server's log."""

    def __init__(self, browser, path: str) -> None:
        self.log = io.StringIO()
        self.server, self.url = serve_in_thread(Explorer(open_map(path), log=self.log))
        self.tab = browser.new_page(viewport={"width": 1300, "height": 1000})
        self.console = []
        self.tab.on("console", lambda m: self.console.append(f"{m.type}: {m.text}")
                    if m.type in ("error", "warning") else None)
        self.tab.on("pageerror", lambda e: self.console.append(f"pageerror: {e}"))

    def open(self, fragment: str = "") -> None:
        self.tab.goto(self.url + fragment)
        self.tab.wait_for_selector("body[data-ready='1']", timeout=30000)

    def close(self) -> None:
        self.tab.close()
        self.server.shutdown()
        self.server.server_close()

    def centre(self, i: int, j: int, n1: int, n2: int) -> dict:
        """Pixel (i, j)'s centre on the map's canvas, in CSS pixels of the canvas."""
        canvas = self.tab.locator("#map")
        x, y, w, h = (float(v) for v in canvas.get_attribute("data-box").split(","))
        scale = canvas.bounding_box()["width"] / float(canvas.get_attribute("width"))
        return {"x": (x + (i + 0.5) * w / n1) * scale,
                "y": (y + (n2 - j - 0.5) * h / n2) * scale}

    def hover(self, i: int, j: int, n1: int, n2: int) -> float:
        self.tab.locator("#map").hover(position=self.centre(i, j, n1, n2))
        value = self.tab.locator("#hover-value")
        return float(value.get_attribute("data-value"))

    def click(self, i: int, j: int, n1: int, n2: int, shift: bool = False) -> None:
        self.tab.locator("#map").click(position=self.centre(i, j, n1, n2),
                                       modifiers=["Shift"] if shift else [])

    def run_value(self, row: str = "#value-row") -> float:
        cell = self.tab.locator(f"{row} td.num").nth(1)
        return float(cell.get_attribute("data-value"))

    def message(self) -> str:
        return self.tab.locator("#message").inner_text()


def _pixel(path: str, name: str):
    """A pixel of the map with a finite value, away from the border, and its value."""
    with h5py.File(path, "r") as f:
        values = f["/sweep/" + name][...]
    n2, n1 = values.shape
    finite = [(i, j) for j in range(1, n2 - 1) for i in range(1, n1 - 2)
              if math.isfinite(values[j, i]) and math.isfinite(values[j, i + 1])]
    assert finite, f"{path}: no finite {name} away from the border"
    i, j = finite[len(finite) // 3]
    return i, j, n1, n2, values


@pytest.mark.parametrize("kind", list(MAPS))
def test_click_a_pixel(browser, maps, shots, kind):
    name = MAPS[kind][1]
    i, j, n1, n2, values = _pixel(maps[kind], name)
    page = Page(browser, maps[kind])
    try:
        page.open(f"#map={name}")
        assert page.hover(i, j, n1, n2) == values[j, i]            # to the bit
        page.click(i, j, n1, n2)
        page.tab.wait_for_selector("#value-row", timeout=30000)
        assert page.run_value() == values[j, i], page.message()   # to the bit
        assert "the same, to the bit" in page.tab.locator("#value-row").inner_text()
        pendulum = page.tab.locator("#pendulum")
        first = pendulum.screenshot()
        time.sleep(0.4)
        second = pendulum.screenshot()
        assert first != second, "the animation does not advance"
        page.click(i + 1, j, n1, n2, shift=True)
        page.tab.wait_for_selector("#separation[data-drawn='1']", timeout=30000)
        assert page.run_value("#value-row-b") == values[j, i + 1]
        time.sleep(0.3)
        page.tab.screenshot(path=os.path.join(shots, f"explore_{kind}.png"), full_page=True)
        assert page.console == [], page.console
        assert "refused" not in page.log.getvalue(), page.log.getvalue()
    finally:
        page.close()


def test_keyboard_alone(browser, maps):
    """Arrow keys move the selected pixel (the value under it is the text shown),
    Enter runs it, Shift+Enter a second one; nothing but the keyboard."""
    i, j, n1, n2, values = _pixel(maps["flip"], "t_flip")
    page = Page(browser, maps["flip"])
    try:
        page.open()
        page.tab.keyboard.press("Tab")                  # the map select, then the map
        page.tab.keyboard.press("Tab")
        assert page.tab.evaluate("document.activeElement.id") == "map"
        ci, cj = n1 // 2, n2 // 2                       # where the selection starts
        for _ in range(abs(i - ci)):
            page.tab.keyboard.press("ArrowRight" if i > ci else "ArrowLeft")
        for _ in range(abs(j - cj)):
            page.tab.keyboard.press("ArrowUp" if j > cj else "ArrowDown")
        hover = page.tab.locator("#hover")
        assert (int(hover.get_attribute("data-i")), int(hover.get_attribute("data-j"))) == (i, j)
        assert float(page.tab.locator("#hover-value").get_attribute("data-value")) == values[j, i]
        page.tab.keyboard.press("Enter")
        page.tab.wait_for_selector("#value-row", timeout=30000)
        assert page.run_value() == values[j, i]
        page.tab.keyboard.press("ArrowRight")
        page.tab.keyboard.press("Shift+Enter")
        page.tab.wait_for_selector("#separation[data-drawn='1']", timeout=30000)
        assert page.run_value("#value-row-b") == values[j, i + 1]
        assert page.console == [], page.console
    finally:
        page.close()


def test_state_in_the_url_and_downloads(browser, maps):
    """A view reloaded from its address shows the same pixels at the same time; the
    downloads are the run's trajectory (HDF5 and CSV)."""
    i, j, n1, n2, values = _pixel(maps["flip"], "t_flip")
    page = Page(browser, maps["flip"])
    try:
        page.open(f"#map=energy_error&i={i}&j={j}&i2={i + 1}&j2={j}&t=1.5")
        page.tab.wait_for_selector("#separation[data-drawn='1']", timeout=30000)
        assert page.tab.locator("#mapname").input_value() == "energy_error"
        with h5py.File(maps["flip"], "r") as f:
            energy_error = f["/sweep/energy_error"][j, i]
        assert page.run_value() == energy_error
        clock = page.tab.locator("#clock").inner_text()
        assert clock.startswith("t = 1.49") or clock.startswith("t = 1.5"), clock
        for kind in ("h5", "csv"):
            href = page.tab.locator(f"#download-{kind}").get_attribute("href")
            with urllib.request.urlopen(page.url + href) as r:
                body = r.read()
            if kind == "h5":
                with h5py.File(io.BytesIO(body), "r") as f:
                    q0 = f.attrs["q0"]
                    assert f.attrs["method"] == "rk4"
                with h5py.File(maps["flip"], "r") as f:
                    theta = (f["/sweep/axis1"][i], f["/sweep/axis2"][j])
                assert np.allclose(q0, np.array(theta) - np.pi / 2, rtol=0, atol=1e-15)
            else:
                rows = list(csv.reader(line for line in io.StringIO(body.decode())
                                       if not line.startswith("#")))
                assert rows[0][:3] == ["t", "q1", "q2"] and float(rows[1][0]) == 0.0
        assert page.console == [], page.console
    finally:
        page.close()


HOSTILE = [
    ("#i=nan&j=3", "i = 'nan'"),
    ("#i=3&j=4&t_end=1e300", "t_end"),
    ("#i=3&j=99999", "j = '99999'"),
    ("#i=-1&j=2", "i = '-1'"),
    ("#map=../../../../etc/passwd", "name = '../../../../etc/passwd'"),
]


@pytest.mark.parametrize("fragment,field", HOSTILE)
def test_hostile_values_refused_on_the_page(browser, maps, fragment, field):
    page = Page(browser, maps["flip"])
    try:
        page.open(fragment)
        message = page.message()
        assert field in message and "\n" not in message.strip(), message
        assert page.tab.locator("#message.error").count() == 1
        assert field in page.log.getvalue() and "refused" in page.log.getvalue()
        with urllib.request.urlopen(page.url + "api/map") as r:   # the server is up
            assert r.status == 200
        # the browser logs a failed request (HTTP 400) as a console error: the only ones
        assert all("400" in line for line in page.console), page.console
    finally:
        page.close()


def test_requests_checked_before_work(maps):
    """Without a browser: every route refuses a hostile request in one line."""
    log = io.StringIO()
    server, url = serve_in_thread(Explorer(open_map(maps["flip"]), log=log))
    try:
        cases = [("api/pixel?i=nan&j=1", 400, "i = 'nan'"),
                 ("api/pixel?i=1&j=1&t_end=1e9", 400, "t_end"),
                 ("api/pixel?i=1&j=1&i=2", 400, "given twice"),
                 ("api/pixel?i=24&j=0", 400, "[0, 23]"),
                 ("api/pixel?i=1", 400, "j is missing"),
                 ("api/values?name=../x", 400, "name = '../x'"),
                 ("../../etc/passwd", 404, "is not served"),
                 ("api/map?x=1", 400, "x = '1'"),
                 ("api/pixel?i=" + "9" * 600 + "&j=1", 400, "characters")]
        for path, status, text in cases:
            try:
                urllib.request.urlopen(url + path)
                raise AssertionError(f"{path}: accepted")
            except urllib.error.HTTPError as e:
                body = e.read().decode()
                assert e.code == status and text in body and body.count("\n") == 1, \
                    (path, e.code, body)
        request = urllib.request.Request(url + "api/pixel?i=1&j=1", method="POST")
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen(request)
        assert e.value.code == 405
        # another Host (a page elsewhere through a name that resolves here): refused
        request = urllib.request.Request(url + "api/map", headers={"Host": "evil.example"})
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen(request)
        assert e.value.code == 403 and "evil.example" in e.value.read().decode()
        # a line end or escape in a value stays escaped in its one line
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen(url + "api/pixel?i=1%0Aforged%1B[2J&j=1")
        body = e.value.read().decode()
        assert body.count("\n") == 1 and "\\n" in body and "\x1b" not in body
        assert log.getvalue().count("refused") == len(cases) + 3
        assert all(line.startswith("dpend explore: ") for line in log.getvalue().splitlines())
    finally:
        server.shutdown()
        server.server_close()


def test_runs_at_once_are_limited(maps):
    """--max-runs: a pixel request beyond the runs in flight is refused ('busy', 503)
    and the server goes on; a finished run is kept and served again without work."""
    import threading
    from dpend.explore._pixel import run_pixel

    started, release = threading.Event(), threading.Event()
    calls = []

    def slow(m, i, j):
        calls.append((i, j))
        started.set()
        release.wait(30)
        return run_pixel(m, i, j)

    log = io.StringIO()
    server, url = serve_in_thread(Explorer(open_map(maps["flip"]), max_runs=1, log=log,
                                           runner=slow))
    try:
        first = threading.Thread(target=urllib.request.urlopen,
                                 args=(url + "api/pixel?i=1&j=1",), daemon=True)
        first.start()
        assert started.wait(30)
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen(url + "api/pixel?i=2&j=1")
        assert e.value.code == 503 and "busy: 1 run in progress" in e.value.read().decode()
        release.set()
        first.join(30)
        with urllib.request.urlopen(url + "api/pixel?i=1&j=1") as r:   # kept: no new run
            assert r.status == 200
        assert calls == [(1, 1)]
        assert "refused GET /api/pixel?i=2&j=1: busy" in log.getvalue()
    finally:
        release.set()
        server.shutdown()
        server.server_close()
