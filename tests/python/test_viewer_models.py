"""contactsim-viewer drawing robot models in a real browser (headless
chromium, Selenium) against a real server: the iiwa's mesh files loaded and
placed at its links' frames, the collision toggle, the joint panel against
pinocchio, ray casts and range-sensor fans, R2D2's primitives and meshes,
a Collada visual in the server's axes and unit, and a replay's robot (docs/viewer.md, "Robot
models"). Skipped without chromium, chromedriver, selenium or pybullet_data."""
import os
import shutil
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from conftest import BUILD
from test_viewer import VIEWER, browser, open_page  # noqa: F401 - the browser fixture

from contactsim.viewer.headless import wait_for
from contactsim.viewer.process import ViewerProcess

pybullet_data = pytest.importorskip("pybullet_data")
DATA = pybullet_data.getDataPath()
IIWA = os.path.join(DATA, "kuka_iiwa", "model.urdf")
R2D2 = os.path.join(DATA, "r2d2.urdf")
BENT = np.array([0.3, 0.8, -0.4, -1.2, 0.5, 0.7, -0.3])  # rad
ARTIFACTS = BUILD / "test-artifacts"
MODEL_DATA = Path(__file__).resolve().parents[1] / "model" / "data"   # the model readers' test files


@pytest.fixture
def models_server(launch):
    return launch(args=("--model-path", DATA))


def _visual_counts(path):
    """(visual elements, of which meshes) of a URDF, read with ElementTree."""
    visuals = ET.parse(path).getroot().findall("link/visual")
    return len(visuals), sum(v.find("geometry/mesh") is not None for v in visuals)


def _viewer(server):
    return ViewerProcess(["--lcm-url", server.url, "--prefix", server.prefix])


def _wait_for_meshes(driver, files):
    """Waits until the page has loaded every mesh file; returns models()."""
    return wait_for(driver, "%s.models().total === %d && %s.models().loaded + %s.models().failed === %d && %s.models()"
                    % (VIEWER, files, VIEWER, VIEWER, files, VIEWER), timeout=60)


def _link_world(driver, link):
    """A link frame's world position in the page's scene graph (None: no visual drawn for it)."""
    p = driver.execute_script(
        "const o = %s.internals.models.root.getObjectByName(arguments[0]); if (!o) return null;"
        "o.updateWorldMatrix(true, false); return Array.from(o.matrixWorld.elements.slice(12, 15));" % VIEWER, link)
    return None if p is None else np.array(p)


def _set_mode(driver, mode):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import Select
    Select(driver.find_element(By.ID, "collision-mode")).select_by_value(mode)
    return driver.execute_script("return %s.collisionShown()" % VIEWER)


# Verifies that the iiwa's eight OBJ visuals load from the bridge and sit at
# the link frames STATE puts them (within 1 um), that the collision toggle
# swaps what is drawn (visuals alone, collision hulls as a wire overlay, the
# hulls alone: the scene graph and the picture change), that the joint
# panel reads pinocchio's configuration back from the poses, and that a
# click on a visual selects its link's body.
def test_iiwa_draws_its_meshes_and_joint_angles(models_server, browser):  # noqa: F811
    pin = pytest.importorskip("pinocchio")
    c = models_server.client
    c.set_gravity((0, 0, 0))
    c.add_plane((0, 0, 1), 0.0)
    iiwa = c.load_model(IIWA, name="iiwa", fixed_base=True)
    pm = pin.buildModelFromUrdf(IIWA)
    pd = pm.createData()
    pin.framesForwardKinematics(pm, pd, BENT)
    iiwa.set_link_poses({f.name: (pd.oMf[i].translation, pd.oMf[i].rotation)
                         for i, f in enumerate(pm.frames) if f.type == pin.FrameType.BODY})
    c.step(1)
    st = c.state()
    visuals, files = _visual_counts(IIWA)
    assert (visuals, files) == (8, 8)
    with _viewer(models_server) as viewer:
        open_page(browser, viewer.url, st.step)
        counts = _wait_for_meshes(browser, files)
        assert counts["failed"] == 0 and counts["bodies"] == 8 and counts["meshes"] >= files, counts
        for link in iiwa.links:
            p, _ = iiwa.link_pose(link, st)
            assert np.abs(_link_world(browser, link) - p).max() < 1e-6, link
        values = browser.execute_script("return %s.jointValues()" % VIEWER)
        got = [values["iiwa/lbr_iiwa_joint_%d" % k] for k in range(1, 8)]
        assert np.abs(np.array(got) - BENT).max() < 1e-6, got
        panel = browser.execute_script("return document.getElementById('joints').textContent")
        assert "iiwa/lbr_iiwa_joint_4" in panel and "%.1f°" % np.degrees(BENT[3]) in panel, panel
        # a click on link 4's visual selects its body
        browser.execute_async_script(
            "const done = arguments[arguments.length - 1];"
            "import('three').then((THREE) => {"
            "  const v = %s.internals, o = v.models.root.getObjectByName('lbr_iiwa_link_4');"
            "  const c = new THREE.Box3().setFromObject(o).getCenter(new THREE.Vector3()).project(v.world.camera);"
            "  const canvas = v.world.renderer.domElement, r = canvas.getBoundingClientRect();"
            "  canvas.dispatchEvent(new MouseEvent('click', { clientX: r.left + (c.x + 1) / 2 * r.width,"
            "                                                  clientY: r.top + (1 - c.y) / 2 * r.height }));"
            "  done(); });" % VIEWER)
        selected = wait_for(browser, "document.getElementById('selection').textContent.startsWith('id ') && "
                            "document.getElementById('selection').textContent")
        assert selected.startswith("id %d " % iiwa.body_id("lbr_iiwa_link_4")), selected
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        pictures = {}
        for mode, shown, models_visible in [("visual", {"solid": 0, "overlay": 0}, True),
                                            ("both", {"solid": 0, "overlay": 8}, True),
                                            ("collision", {"solid": 8, "overlay": 0}, False)]:
            assert _set_mode(browser, mode) == shown, mode
            assert browser.execute_script("return %s.internals.models.root.visible" % VIEWER) is models_visible
            wait_for(browser, "!%s.internals.world.dirty" % VIEWER)
            pictures[mode] = browser.get_screenshot_as_png()
            (ARTIFACTS / ("viewer_iiwa_%s.png" % mode)).write_bytes(pictures[mode])
        assert len(set(pictures.values())) == 3, "each collision mode draws another picture"


# Verifies that a ray cast of another client and a range sensor's fan are
# drawn: every ray as a line, a point at each hit, as many hits as the
# server reports (rays at a box hit it, the rest miss), a normal line at
# each of the cast's hits, and that the rays toggle hides them.
def test_ray_casts_and_range_fans_are_drawn(server, browser):  # noqa: F811
    c = server.client
    c.set_gravity((0, 0, 0))
    c.add_box((0.5, 0.5, 0.5), position=(3, 0, 0), fixed=True)
    carrier = c.add_sphere(0.1, position=(0, 0, 0))
    angles = np.radians(np.linspace(-60, 60, 13))   # |angle| < atan(0.5 / 2.5) hit the box
    fan = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=1)
    c.add_range_sensor(carrier, "lidar", fan, 10.0, origin=(0.1, 0, 0))
    c.step(1)
    deadline = time.monotonic() + 5.0   # SENSORS comes with the STEP's STATE, maybe after its reply
    while c.sensors() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    reading = c.sensors()
    fan_hits = int(reading.ranges["lidar"]["hit"].sum())
    assert 0 < fan_hits < len(angles)
    with _viewer(server) as viewer:
        open_page(browser, viewer.url)
        hits = c.ray_cast([[0, 0, 2], [0, 0, 2], [3, 0, 2]], [[1, 0, 0], [3, 0, -2], [0, 0, -1]], 5.0)
        assert list(hits.hit) == [False, True, True]
        c.step(1)
        drawn = wait_for(browser, "%s.rays().cast.rays === 3 && %s.rays().sensors.rays === %d && %s.rays()"
                         % (VIEWER, VIEWER, len(angles), VIEWER))
        assert drawn == {"cast": {"rays": 3, "hits": 2}, "sensors": {"rays": len(angles), "hits": fan_hits}}
        # a normal line at each of the cast's hits; a range reading carries no normals
        assert browser.execute_script("return %s.internals.rays.normals.geometry.drawRange.count" % VIEWER) == 4
        # the fan starts at the sensor's origin on its body
        start = browser.execute_script(
            "return Array.from(%s.internals.rays.lines.geometry.getAttribute('position').array.slice(18, 21))"
            % VIEWER)
        assert np.abs(np.array(start) - [0.1, 0, 0]).max() < 1e-6, start
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        browser.save_screenshot(str(ARTIFACTS / "viewer_rays.png"))
        browser.find_element("id", "show-rays").click()
        assert browser.execute_script("return %s.internals.rays.lines.visible" % VIEWER) is False


# Verifies that R2D2 renders: its box, cylinder and sphere visuals built in
# the page and its STL meshes loaded, every link's group at its body.
def test_r2d2_renders(models_server, browser):  # noqa: F811
    c = models_server.client
    c.add_plane((0, 0, 1), 0.0)
    r2d2 = c.load_model(R2D2, name="r2d2", position=(0, 0, 0.5))
    c.step(1)
    st = c.state()
    visuals, files = _visual_counts(R2D2)
    with _viewer(models_server) as viewer:
        open_page(browser, viewer.url, st.step)
        counts = _wait_for_meshes(browser, files)
        assert counts["failed"] == 0 and counts["meshes"] >= visuals, counts
        assert counts["bodies"] == len({r2d2.body_id(l) for l in r2d2.links})
        with_visuals = {l.get("name") for l in ET.parse(R2D2).getroot().findall("link") if l.find("visual") is not None}
        for link in r2d2.links:
            p, _ = r2d2.link_pose(link, st)
            drawn = _link_world(browser, link)
            assert (drawn is not None) == (link in with_visuals), link
            if drawn is not None:
                assert np.abs(drawn - p).max() < 1e-6, link
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        browser.save_screenshot(str(ARTIFACTS / "viewer_r2d2.png"))


# Verifies that a Collada visual is drawn as the server reads the same file
# (docs/models.md, "Meshes"): its <unit> applied (centimetres to metres),
# its node's transform kept and its Z_UP axis not turned to three.js's y up,
# so the drawn tetrahedron spans what the collision hull of the file does.
def test_collada_visual_keeps_the_files_axes_and_unit(server, browser, tmp_path):  # noqa: F811
    shutil.copy(MODEL_DATA / "tetra_cm.dae", tmp_path / "tetra_cm.dae")
    (tmp_path / "tetra.urdf").write_text("""<robot name="tetra"><link name="body">
      <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
      <collision><geometry><mesh filename="tetra_cm.dae"/></geometry></collision>
      <visual><geometry><mesh filename="tetra_cm.dae"/></geometry></visual></link></robot>""")
    c = server.client
    c.load_model(str(tmp_path / "tetra.urdf"), name="tetra", position=(0, 0, 1), fixed_base=True)
    c.step(1)
    with _viewer(server) as viewer:
        open_page(browser, viewer.url, c.state().step)
        assert _wait_for_meshes(browser, 1)["failed"] == 0
        box = browser.execute_async_script(
            "const done = arguments[arguments.length - 1];"
            "import('three').then((THREE) => {"
            "  const o = %s.internals.models.root.getObjectByName('body'); o.updateWorldMatrix(true, true);"
            "  const b = new THREE.Box3().setFromObject(o, true); done([b.min.toArray(), b.max.toArray()]); });"
            % VIEWER)
    # corners at 0 and 100, 200, 300 cm, moved 50 cm along x by the node, the link at z = 1 m
    np.testing.assert_allclose(box, [[0.5, 0.0, 1.0], [1.5, 2.0, 4.0]], atol=1e-6)


# Verifies that a replay with the run's snapshot draws the robot too: its
# meshes served from the snapshot's mesh folders, each link where the
# recorded STATE puts it.
def test_replay_draws_the_model_from_the_snapshot(models_server, browser, tmp_path):  # noqa: F811
    from lcm_recorder import LcmRecorder
    c = models_server.client
    iiwa = c.load_model(IIWA, name="iiwa", fixed_base=True)
    snapshot = tmp_path / "iiwa.snapshot"
    c.snapshot(path=str(snapshot))
    log_path = tmp_path / "run.lcmlog"
    states = []
    with LcmRecorder(models_server.url, models_server.prefix + "_.*", log_path):
        for _ in range(3):
            c.step(20)
            states.append(c.state())
    with ViewerProcess(["--log", str(log_path), "--snapshot", str(snapshot)]) as viewer:
        open_page(browser, viewer.url)
        assert _wait_for_meshes(browser, 8)["failed"] == 0
        k = browser.execute_script("return %s.timelineSteps()" % VIEWER).index(states[2].step)
        browser.execute_script("%s.seek(arguments[0])" % VIEWER, k)
        wait_for(browser, "%s.step() === %d" % (VIEWER, states[2].step))
        for link in iiwa.links:
            p, _ = iiwa.link_pose(link, states[2])
            assert np.abs(_link_world(browser, link) - p).max() < 1e-6, link
