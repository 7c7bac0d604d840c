"""Headless Debian chromium driven by Selenium, for the viewer's tests and
scripts (tests/python/test_viewer.py, bench/scripts/viewer_bench.py,
scripts/viewer_screenshot.py). Selenium is a test dependency, imported here only."""
import os
import shutil
import time

CHROMIUM_NAMES = ("chromium", "chromium-browser", "google-chrome")
DRIVER_NAMES = ("chromedriver",)


def find_browser():
    """(chromium path, chromedriver path), either None when missing."""
    browser = next((p for p in map(shutil.which, CHROMIUM_NAMES) if p), None)
    driver = next((p for p in map(shutil.which, DRIVER_NAMES) if p), None)
    return browser, driver


def start_browser(width=1280, height=800):
    """A Selenium WebDriver on headless chromium with WebGL in software
    (SwiftShader: no GPU on the machines that run this)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    browser, driver = find_browser()
    if browser is None or driver is None:
        raise FileNotFoundError("chromium and chromedriver are needed (make deps installs them)")
    opts = webdriver.ChromeOptions()
    opts.binary_location = browser
    for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--use-angle=swiftshader",
                "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist", "--window-size=%d,%d" % (width, height),
                # the page keeps drawing when no one looks at it
                "--disable-background-timer-throttling", "--disable-renderer-backgrounding"):
        opts.add_argument(arg)
    return webdriver.Chrome(service=Service(driver, log_output=os.devnull), options=opts)


def wait_for(driver, script, timeout=20.0, interval=0.05):
    """Runs `return <script>` in the page until it is truthy; returns the value."""
    deadline = time.monotonic() + timeout
    while True:
        value = driver.execute_script("return " + script)
        if value:
            return value
        if time.monotonic() > deadline:
            raise TimeoutError("page did not reach %r within %gs" % (script, timeout))
        time.sleep(interval)
