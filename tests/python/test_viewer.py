"""contactsim-viewer in a real browser: headless chromium driven by Selenium
against a real server (docs/viewer.md). Skipped when chromium, chromedriver
or selenium is missing (make deps installs them)."""
import time
from pathlib import Path

import numpy as np
import pytest

from conftest import BUILD
from lcm_recorder import LcmRecorder

from contactsim.viewer.process import ViewerProcess  # noqa: E402

from contactsim.viewer.headless import find_browser, wait_for  # noqa: E402

ARTIFACTS = BUILD / "test-artifacts"
TOLERANCE = 1e-3   # m
VIEWER = "window.contactsimViewer"


@pytest.fixture(scope="module")
def browser():
    if None in find_browser():
        pytest.skip("chromium or chromedriver is not installed (make deps: apt chromium chromium-driver)")
    pytest.importorskip("selenium", reason="selenium is not installed (make deps)")
    from contactsim.viewer.headless import start_browser
    from contactsim.viewer.server import THREE_DIR
    assert (Path(THREE_DIR) / "build" / "three.module.js").is_file(), \
        "three.js is not installed in %s: run `make deps` (npm ci)" % THREE_DIR
    driver = start_browser()
    yield driver
    driver.quit()


def every_shape(c):
    """A plane and one body of every other kind, two of them jointed; returns the hinge's id."""
    c.add_plane((0, 0, 1), 0.0)
    ball = c.add_sphere(0.2, position=(0, 0, 1.0))
    box = c.add_box((0.2, 0.3, 0.1), position=(1, 0, 0.5), orientation=(0.9, 0.1, 0.3, 0.2))
    c.add_capsule(0.1, 0.3, position=(-1, 0, 0.8))
    c.add_convex([[0, 0, 0], [0.4, 0, 0], [0, 0.4, 0], [0, 0, 0.4]], position=(0, 1, 0.6))
    return c.add_joint("ball", ball, box, anchor=(0.5, 0, 0.75))


def open_page(driver, url, step=None):
    driver.get(url)
    wait_for(driver, "%s && %s.framesDrawn() > 0" % (VIEWER, VIEWER))
    if step is not None:
        wait_for(driver, "%s.step() === %d" % (VIEWER, step))


def page_positions(driver):
    return {int(k): np.array(v) for k, v in driver.execute_script("return %s.bodies()" % VIEWER).items()}


def assert_poses(page, expected):
    """Every body the page draws sits where the state says, within TOLERANCE."""
    assert page, "the page draws no body"
    for body_id, p in page.items():
        assert np.abs(p - expected[body_id]).max() < TOLERANCE, (body_id, p, expected[body_id])


# Verifies that the page draws every body where STATE says, with every shape
# kind and the joint from the snapshot catalog, and saves a screenshot.
def test_live_page_draws_state(server, browser):
    c = server.client
    every_shape(c)
    c.step(60)
    st = c.state()
    with ViewerProcess(["--lcm-url", server.url, "--prefix", server.prefix]) as viewer:
        open_page(browser, viewer.url, st.step)
        page = page_positions(browser)
        assert_poses(page, {i: b.position for i, b in st.bodies.items()})
        assert set(page) == set(st.bodies) - {1}   # the plane is a static square, not an instance
        kinds = browser.execute_script("return [...%s.internals.bodies.catalog.values()].map(b => b.shape.kind)"
                                       % VIEWER)
        assert sorted(kinds) == ["box", "capsule", "convex", "plane", "sphere"]
        assert browser.execute_script("return %s.internals.joints.joints.length" % VIEWER) == 1
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        browser.save_screenshot(str(ARTIFACTS / "viewer_live.png"))


# Verifies that the page's pause button pauses the server and its method
# select switches the contact method, both as STATUS reports them, that the
# panel shows the method's contract and that a refused switch says why.
def test_page_commands_reach_server(server, browser):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select
    c = server.client
    c.add_plane((0, 0, 1), 0.0)
    c.add_sphere(0.1, position=(0, 0, 0.5), restitution=0.5)
    c.set_mode("realtime")
    c.resume()
    c.wait_for_status(lambda s: not s.paused, timeout=5)
    with ViewerProcess(["--lcm-url", server.url, "--prefix", server.prefix]) as viewer:
        open_page(browser, viewer.url)
        browser.find_element(By.ID, "btn-pause").click()
        assert c.wait_for_status(lambda s: s.paused, timeout=5).paused
        Select(browser.find_element(By.ID, "method-select")).select_by_value("penalty")
        browser.find_element(By.ID, "btn-method").click()
        assert c.wait_for_status(lambda s: s.method == "penalty", timeout=5).method == "penalty"
        replies = wait_for(browser, "%s.replies().length >= 2 && %s.replies()" % (VIEWER, VIEWER))
        assert [(r["cmd"], r["ok"]) for r in replies] == [("pause", True), ("method", True)]
        # the panel shows what the method simulates (docs/physics.md, "Method
        # contract"), and a switch to one that cannot honour the world (barrier:
        # the sphere has restitution 0.5) comes back refused with why
        contract = "document.getElementById('ro-contract').textContent"
        shown = wait_for(browser, "%s.includes('regularized: tangential spring') && %s" % (contract, contract))
        assert shown.startswith("joints=yes; restitution=yes; kinematic=yes; contact_forces=yes; friction=")
        Select(browser.find_element(By.ID, "method-select")).select_by_value("barrier")
        browser.find_element(By.ID, "btn-method").click()
        replies = wait_for(browser, "%s.replies().length >= 3 && %s.replies()" % (VIEWER, VIEWER))
        assert (replies[2]["cmd"], replies[2]["ok"]) == ("method", False)
        assert "barrier does not simulate restitution" in replies[2]["message"], replies[2]["message"]
        assert c.wait_for_status(lambda s: s.step >= 0, timeout=5).method == "penalty"


# Verifies that a recorded log replays without a server: scrubbing the
# timeline to STATE k shows the poses of that STATE.
def test_replay_scrub_matches_recorded_state(server, browser, tmp_path):
    c = server.client
    every_shape(c)
    snapshot = tmp_path / "shapes.snapshot"
    c.snapshot(path=str(snapshot))
    log_path = tmp_path / "run.lcmlog"
    states = []
    with LcmRecorder(server.url, server.prefix + "_.*", log_path):
        for _ in range(12):
            c.step(5)
            states.append(c.state())
    with ViewerProcess(["--log", str(log_path), "--snapshot", str(snapshot)]) as viewer:
        open_page(browser, viewer.url)
        steps = browser.execute_script("return window.contactsimViewer.timelineSteps()")
        k = steps.index(states[7].step)
        browser.execute_script("const s = document.getElementById('timeline'); s.value = arguments[0];"
                               "s.dispatchEvent(new Event('input'));", k)
        wait_for(browser, "%s.step() === %d" % (VIEWER, states[7].step))
        time.sleep(0.1)   # the animation frame that drew it has run; nothing newer is asked for
        assert_poses(page_positions(browser), {i: b.position for i, b in states[7].bodies.items()})
