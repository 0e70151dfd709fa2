"""The HTML report in a real browser (headless Chromium from Debian's
``chromium`` and ``chromium-driver`` packages, which .ci/run installs):
no console errors, every plot drawn with a non-zero size."""
from __future__ import annotations

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


def test_report_in_headless_chromium(tmp_path, capsys):
    code = main(["run", str(CASES / "profile"), str(CASES / "short-move-overcut"),
                 "--out", str(tmp_path), "--no-compare"])
    capsys.readouterr()
    assert code == 0
    index = tmp_path / "index.html"
    driver = _driver()
    try:
        driver.get(index.as_uri())
        sizes = driver.execute_script(
            "return Array.from(document.images).map(i => [i.complete, i.naturalWidth, "
            "i.naturalHeight, i.getBoundingClientRect().width, i.getBoundingClientRect().height]);")
        logs = driver.get_log("browser")
        title = driver.title
    finally:
        driver.quit()
    assert title == "ccopt run"
    assert len(sizes) == 6, sizes            # three plots for each of the two cases
    for complete, nw, nh, w, h in sizes:
        assert complete and nw > 0 and nh > 0 and w > 0 and h > 0, sizes
    errors = [entry for entry in logs if entry.get("level") == "SEVERE"]
    assert errors == [], errors
