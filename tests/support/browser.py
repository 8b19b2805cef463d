"""Headless Chromium through Selenium, for the page's tests and its benchmark.

:func:`chromium` starts one browser (``--headless=new``, no sandbox, a 1400x900 window,
the browser log kept); :func:`missing` says why none can be started here (``None`` where
one can): Chromium at :data:`CHROMIUM`, its driver, Selenium.
"""

from __future__ import annotations

import importlib.util
import shutil
from pathlib import Path

CHROMIUM = Path("/usr/bin/chromium")
CHROMEDRIVER = shutil.which("chromedriver") or "/usr/bin/chromedriver"


def missing() -> str | None:
    """Why no browser can be started here, or ``None``."""
    if importlib.util.find_spec("selenium") is None:
        return "Selenium is not installed (pip install linkage_sym[page-tests])"
    if not CHROMIUM.exists():
        return f"no Chromium at {CHROMIUM} (apt-get install chromium chromium-driver)"
    if not Path(CHROMEDRIVER).exists():
        return "no chromedriver (apt-get install chromium-driver)"
    return None


def chromium():
    """A headless Chromium driven by Selenium (the caller quits it)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--window-size=1400,900"):
        opts.add_argument(arg)
    opts.binary_location = str(CHROMIUM)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=opts)
    driver.set_script_timeout(120)
    return driver


def open_page(driver, path):
    """Open the page at ``path`` and return its ``window.linkageSym.summary()``; the
    browser log is drained first, so what a test reads of it is this page's."""
    driver.get(path.as_uri())
    driver.get_log("browser")
    return driver.execute_script("return window.linkageSym.summary()")


def twelve(scene):
    """12 steps of the scene's sweep evenly across it: their indices, their driver values
    (D, 12) and the page's driver lists."""
    import numpy as np

    idx = np.round(np.linspace(0, scene.steps - 1, 12)).astype(int)
    Q = np.array([np.linspace(d.start, d.stop, d.steps)[idx] for d in scene.drivers])
    return idx, Q, Q.T.tolist()
