"""contactsim-viewer drawing static triangle meshes and heightfields in a
real browser (headless chromium, Selenium) against a real server
(docs/viewer.md, "The page"): each body's geometry as the server stores it,
at its pose, and ray hits on them. Skipped without chromium, chromedriver
or selenium."""
import numpy as np

from conftest import BUILD
from test_viewer import VIEWER, browser, open_page  # noqa: F401 - the browser fixture

from contactsim.viewer.headless import wait_for
from contactsim.viewer.process import ViewerProcess

ARTIFACTS = BUILD / "test-artifacts"
FLOAT32 = 1e-5   # m: the page's vertices are float32 (7 digits at coordinates of a few metres)

# a square pyramid: apex over a 1 x 0.6 m base, four sides and the base's two triangles
PYRAMID = np.array([[-0.5, -0.3, 0], [0.5, -0.3, 0], [0.5, 0.3, 0], [-0.5, 0.3, 0], [0, 0, 0.8]])
PYRAMID_TRIANGLES = np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4], [0, 2, 1], [0, 3, 2]])


def _rotation(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _about_z(angle):
    return (np.cos(angle / 2), 0.0, 0.0, np.sin(angle / 2))


def _grid(rows, cols, spacing, heights):
    """The samples of a heightfield in its body frame (service/collision/height_field.h)."""
    c, r = np.meshgrid(np.arange(cols), np.arange(rows))
    return np.stack([(c - (cols - 1) / 2) * spacing[0], (r - (rows - 1) / 2) * spacing[1], heights], -1).reshape(-1, 3)


def _drawn(driver, body):
    """The drawn object of a body: vertex and index counts, its world box, whether it has vertex colours."""
    return driver.execute_async_script(
        "const done = arguments[arguments.length - 1];"
        "import('three').then((THREE) => {"
        "  const slot = %s.internals.bodies.slots.get(arguments[0]); if (!slot || !slot.object) return done(null);"
        "  const o = slot.object; o.updateWorldMatrix(true, true);"
        "  const m = o.children[0], g = m.geometry, b = new THREE.Box3().setFromObject(o, true);"
        "  done({vertices: g.getAttribute('position').count, indices: g.index.count,"
        "        colours: !!g.getAttribute('color') && m.material.vertexColors,"
        "        box: [b.min.toArray(), b.max.toArray()]}); });" % VIEWER, body)


def _hit_on_drawn(driver, body, origin, direction):
    """Where the page's own raycaster meets a body's drawn object, or None."""
    return driver.execute_async_script(
        "const done = arguments[arguments.length - 1];"
        "import('three').then((THREE) => {"
        "  const o = %s.internals.bodies.slots.get(arguments[0]).object;"
        "  const r = new THREE.Raycaster(new THREE.Vector3(...arguments[1]), new THREE.Vector3(...arguments[2]));"
        "  const h = r.intersectObject(o, true); done(h.length ? h[0].point.toArray() : null); });" % VIEWER,
        body, list(origin), list(direction))


# Verifies that a triangle mesh and a heightfield are drawn from the
# snapshot's geometry: the mesh with its vertices and triangles, the
# heightfield as a rows x cols grid of two triangles a cell coloured by
# height, each posed as the server has it (the world box of the drawn
# object equals that of the posed vertices); and that a ray cast on them
# is drawn with its hits lying on the drawn surfaces (screenshot
# viewer_surfaces.png).
def test_meshes_and_heightfields_are_drawn(server, browser):  # noqa: F811
    c = server.client
    c.set_gravity((0, 0, 0))
    mesh_q, mesh_p = _about_z(np.pi / 3), np.array([2.0, 0.5, 0.0])
    mesh = c.add_mesh(PYRAMID, PYRAMID_TRIANGLES, position=mesh_p, orientation=mesh_q)
    rows, cols, spacing = 6, 9, (0.4, 0.25)
    x = np.arange(cols) / (cols - 1)
    heights = 0.3 * np.outer(np.linspace(-1, 1, rows), np.sin(3 * x)) + 0.05 * np.arange(rows)[:, None]
    field_q, field_p = _about_z(-np.pi / 5), np.array([-2.0, 0.0, -0.5])
    field = c.add_heightfield(heights, spacing, position=field_p, orientation=field_q)
    c.step(1)
    mesh_world = PYRAMID @ _rotation(mesh_q).T + mesh_p
    field_world = _grid(rows, cols, spacing, heights) @ _rotation(field_q).T + field_p
    # straight down onto the apex's side and onto the terrain
    origins = np.array([mesh_p + [0.1, 0.05, 2.0], field_p + [0.3, -0.2, 2.0], [0.0, 0.0, 2.0]])
    down = np.tile([0.0, 0.0, -1.0], (3, 1))
    with ViewerProcess(["--lcm-url", server.url, "--prefix", server.prefix]) as viewer:
        open_page(browser, viewer.url, c.state().step)
        got = {b: _drawn(browser, b) for b in (mesh, field)}
        assert got[mesh]["vertices"] == len(PYRAMID) and got[mesh]["indices"] == PYRAMID_TRIANGLES.size
        assert not got[mesh]["colours"]
        np.testing.assert_allclose(got[mesh]["box"], [mesh_world.min(0), mesh_world.max(0)], atol=FLOAT32)
        assert got[field]["vertices"] == rows * cols and got[field]["indices"] == 6 * (rows - 1) * (cols - 1)
        assert got[field]["colours"]
        np.testing.assert_allclose(got[field]["box"], [field_world.min(0), field_world.max(0)], atol=FLOAT32)
        hits = c.ray_cast(origins, down, 5.0)
        assert list(hits.hit) == [True, True, False] and list(hits.body_ids[:2]) == [mesh, field]
        c.step(1)
        drawn = wait_for(browser, "%s.rays().cast.rays === 3 && %s.rays()" % (VIEWER, VIEWER))
        assert drawn["cast"] == {"rays": 3, "hits": 2}
        for k, body in enumerate((mesh, field)):
            on_page = _hit_on_drawn(browser, body, origins[k], down[k])
            np.testing.assert_allclose(on_page, hits.points[k], atol=FLOAT32)
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        browser.save_screenshot(str(ARTIFACTS / "viewer_surfaces.png"))
