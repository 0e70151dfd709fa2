"""The HTML report in a real browser (headless Chromium from Debian's
``chromium`` and ``chromium-driver`` packages, which .ci/run installs), at
1280 px: no page scrolls sideways, every plot loads with a size, no console
error, the fastest certified variant is marked and a case's page opens from
the index. Screenshots of the index and of case pages are stored in
build/report-screenshots/ for review."""
from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from ccopt.cli import main

pytestmark = pytest.mark.slow  # the quick tier (-m "not slow") leaves these out

CASES = Path(__file__).resolve().parents[2] / "cases"


def _driver():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_path = shutil.which("chromedriver")
    if not chromium or not driver_path:
        pytest.fail("headless Chromium is required for this test: install Debian's chromium and "
                    "chromium-driver (.ci/run does this when they are missing)")
    opts = webdriver.ChromeOptions()
    opts.binary_location = chromium
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                 "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--no-first-run"):
        opts.add_argument(flag)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(driver_path), options=opts)


#: the review copies of the screenshots (build/ is not in git)
SCREENSHOTS = Path(__file__).resolve().parents[2] / "build" / "report-screenshots"
#: the width the report must fit without scrolling sideways
WIDTH = 1280

_IMAGES = ("return Array.from(document.images).map(i => [i.complete, i.naturalWidth, "
           "i.naturalHeight, i.getBoundingClientRect().width, i.getBoundingClientRect().height]);")
_SIDEWAYS = "return document.documentElement.scrollWidth - document.documentElement.clientWidth;"


def _page_checks(driver, expected_images: int) -> None:
    """Every image loaded with a size; nothing scrolls sideways; no console error."""
    sizes = driver.execute_script(_IMAGES)
    assert len(sizes) == expected_images, sizes
    for complete, nw, nh, w, h in sizes:
        assert complete and nw > 0 and nh > 0 and w > 0 and h > 0, sizes
    assert driver.execute_script(_SIDEWAYS) <= 0, driver.current_url
    errors = [e for e in driver.get_log("browser") if e.get("level") == "SEVERE"]
    assert errors == [], errors


def _screenshot(driver, name: str) -> None:
    """The whole page as PNG into :data:`SCREENSHOTS`, for review."""
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    height = driver.execute_script("return document.documentElement.scrollHeight;")
    driver.set_window_size(WIDTH, min(max(height, 600), 8000))
    driver.save_screenshot(str(SCREENSHOTS / name))
    driver.set_window_size(WIDTH, 900)


def test_report_in_headless_chromium(tmp_path, capsys):
    # a long thin Fagor part (zoomed plots), a case with a gouge, and a case
    # whose comparison has certified variants of different cycle times
    code = main(["run", str(CASES / "fagor-g136-g138"), str(CASES / "short-move-overcut"),
                 str(CASES / "leadin-inside-line"), "--out", str(tmp_path),
                 "--variants", "pmac,linuxcnc,tangent-arc", "--workers", "2"])
    capsys.readouterr()
    assert code == 0
    rows = {r["name"]: r for r in json.loads((tmp_path / "summary.json").read_text())["cases"]}
    variants = rows["leadin-inside-line"]["compare"]
    certified = [v for v in variants if v["certified"] and v["status"] == "ok"]
    winner = min(certified, key=lambda v: v["duration"])["name"]
    driver = _driver()
    try:
        driver.set_window_size(WIDTH, 900)
        driver.get((tmp_path / "index.html").as_uri())
        assert driver.title == "ccopt run"
        _page_checks(driver, 0)
        _screenshot(driver, "index.png")
        # the case page opens from the index
        driver.find_element("link text", "leadin-inside-line").click()
        assert driver.current_url.endswith("/leadin-inside-line.report.html")
        assert driver.find_element("tag name", "h1").text.startswith("leadin-inside-line")
        _page_checks(driver, 3)
        marked = driver.find_elements("css selector", "tr.winner")
        assert len(marked) == 1 and marked[0].text.split()[:3] == [winner, "fastest", "certified"]
        _screenshot(driver, "case-leadin-inside-line.png")
        for name in ("fagor-g136-g138", "short-move-overcut"):
            driver.get((tmp_path / f"{name}.report.html").as_uri())
            _page_checks(driver, 3)
        _screenshot(driver, "case-short-move-overcut.png")
    finally:
        driver.quit()
