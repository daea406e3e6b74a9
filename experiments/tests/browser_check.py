"""Browser test of the HTML experiment report (run by ctest through
tests/experiments/test_experiments_scripts.cpp, ExperimentScripts.HtmlReportInHeadlessChromium).

    /usr/bin/python3 experiments/tests/browser_check.py [report.html]

Without an argument it first makes a report: experiments/channel_count.py --quick with the fake
renderer (experiments/tests/fake_render.py) and the real compare / merge from $IRIS_BUILD_DIR.
Then it opens the page in Debian's headless Chromium through chromedriver (python3-selenium) and
checks, as a reader would see it: no console errors; every image and plot is loaded (naturalWidth
> 0); the comparison canvas is drawn; clicking "flip", dragging the swipe and choosing the error
map each change the pixels shown; hovering prints pixel values. Exit 0 = pass, 1 = fail, 77 = the
browser or its driver is not installed (ctest reports a skip, except under CI=true)."""
from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
SKIP = 77


def make_report(tmp: Path) -> Path:
    """channel_count --quick with the fake renderer: the real report code on fast fake renders."""
    build = Path(os.environ.get("IRIS_BUILD_DIR", REPO / "build")).resolve()
    bdir = tmp / "build"
    bdir.mkdir()
    render = bdir / "render"
    render.write_text(f"#!/bin/sh\nexec {sys.executable} {HERE / 'fake_render.py'} \"$@\"\n")
    render.chmod(0o755)
    for tool in ("compare", "merge"):
        (bdir / tool).symlink_to(build / tool)
    scene = tmp / "scene.xml"
    scene.write_text('<?xml version="1.0"?>\n<scene version="3.0.0">\n    <default name="res" value="16"/>\n'
                     '    <bsdf type="diffuse"/>\n</scene>\n')
    out = tmp / "out"
    proc = subprocess.run([sys.executable, str(REPO / "experiments" / "channel_count.py"), "--quick", "--build-dir",
                           str(bdir), "--out", str(out), "--scene", str(scene), "--parallel", "2"],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        raise SystemExit(f"FAIL: making the report failed:\n{proc.stderr}")
    return out / "report.html"


def canvas_digest(driver) -> str:
    data = driver.execute_script(
        "var c=document.querySelector('.viewer canvas.image');"
        "return Array.from(c.getContext('2d').getImageData(0,0,c.width,c.height).data).join(',');")
    return hashlib.sha1(data.encode()).hexdigest()


def check(page: Path) -> list:
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By

    failures = []
    profile = tempfile.mkdtemp(prefix="iris_chromium_")
    opts = Options()
    opts.binary_location = CHROMIUM
    # The flags that work on this machine (/work/.library/env/machines/cpp.md): no sandbox as root,
    # no GPU, and no background networking (the network is closed).
    for flag in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--disable-dev-shm-usage", f"--user-data-dir={profile}", "--window-size=1200,900"):
        opts.add_argument(flag)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=opts)
    try:
        driver.set_page_load_timeout(30)
        driver.get(page.resolve().as_uri())
        deadline = time.time() + 10
        while time.time() < deadline and not driver.execute_script("return (window.irisViewers||[]).length"):
            time.sleep(0.1)
        viewers = driver.execute_script("return (window.irisViewers||[]).length")
        if not viewers:
            failures.append("no image comparison viewer was created")
        images = driver.execute_script(
            "return Array.from(document.images).map(function(i){return [i.alt, i.complete, i.naturalWidth];});")
        if not images:
            failures.append("the page has no plots or figures")
        for alt, complete, width in images:
            if not (complete and width > 0):
                failures.append(f"image '{alt}' is not loaded (naturalWidth {width})")
        external = driver.execute_script(
            "return Array.from(document.querySelectorAll('[src]')).map(function(e){return e.getAttribute('src');})"
            ".filter(function(s){return !/^data:/.test(s);});")
        if external:
            failures.append(f"the page loads external resources: {external[:3]}")
        if viewers:
            size = driver.execute_script("var c=document.querySelector('.viewer canvas.image');return [c.width,c.height];")
            if not (size[0] > 0 and size[1] > 0):
                failures.append(f"comparison canvas has size {size}")
            canvas = driver.find_element(By.CSS_SELECTOR, ".viewer canvas.image")
            before = canvas_digest(driver)
            driver.find_element(By.CSS_SELECTOR, ".viewer button.flip").click()   # swipe → flip (reference)
            flipped = canvas_digest(driver)
            if flipped == before:
                failures.append("clicking 'flip' did not change the shown image")
            driver.find_element(By.CSS_SELECTOR, ".viewer button.flip").click()   # back to the test image
            if canvas_digest(driver) == flipped:
                failures.append("clicking 'flip' again did not change the shown image back")
            driver.find_element(By.CSS_SELECTOR, ".viewer input[value=swipe]").click()
            swiped = canvas_digest(driver)
            w = canvas.size["width"]
            ActionChains(driver).move_to_element_with_offset(canvas, -w // 2 + 2, 0).click_and_hold() \
                .move_by_offset(w - 4, 0).release().perform()
            if canvas_digest(driver) == swiped:
                failures.append("dragging the swipe across the image did not change it")
            driver.find_element(By.CSS_SELECTOR, ".viewer input[value=error]").click()
            if canvas_digest(driver) == swiped:
                failures.append("the error map looks like the swipe view")
            ActionChains(driver).move_to_element(canvas).move_by_offset(1, 1).perform()
            readout = driver.find_element(By.CSS_SELECTOR, ".viewer .readout").text
            if "pixel (" not in readout or "reference:" not in readout:
                failures.append(f"hovering shows no pixel values: {readout!r}")
            zoom = driver.find_element(By.CSS_SELECTOR, ".viewer .zoom-value").text
            driver.find_element(By.CSS_SELECTOR, ".viewer button.zin").click()
            if driver.find_element(By.CSS_SELECTOR, ".viewer .zoom-value").text == zoom:
                failures.append("the zoom button did not change the zoom")
        for entry in driver.get_log("browser"):
            if entry.get("level") == "SEVERE":
                failures.append(f"console error: {entry.get('message')}")
    finally:
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)
    return failures


def main(argv) -> int:
    if not (os.path.exists(CHROMIUM) and os.path.exists(CHROMEDRIVER)):
        print(f"SKIP: {CHROMIUM} or {CHROMEDRIVER} missing (apt-get install chromium chromium-driver)")
        return SKIP
    try:
        import selenium  # noqa: F401
    except ImportError:
        print("SKIP: python3-selenium missing (apt-get install python3-selenium)")
        return SKIP
    start = time.time()
    tmp = Path(tempfile.mkdtemp(prefix="iris_browser_"))
    try:
        page = Path(argv[0]) if argv else make_report(tmp)
        failures = check(page)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    for f in failures:
        print(f"FAIL: {f}")
    print(f"{'FAILED' if failures else 'PASSED'}: {page.name} in headless Chromium ({time.time() - start:.1f} s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
