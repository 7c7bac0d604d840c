"""contactsim-viewer drawing static triangle meshes and heightfields in a
real browser (headless chromium, Selenium) against a real server
(docs/viewer.md, "The page", "Large surfaces"): each body's geometry as the
server stores it, at its pose, and ray hits on them; a million-sample
heightfield and a 100,000-triangle mesh whole; refused surfaces as markers
with their reasons. Skipped without chromium, chromedriver or selenium."""
import numpy as np

from conftest import BUILD
from lcm_recorder import LcmRecorder
from test_viewer import VIEWER, browser, open_page  # noqa: F401 - the browser fixture
from test_viewer_surface_payload import TETRA, heightfield, mesh, snapshot

from contactsim.viewer.catalog import read_catalog

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
# is drawn with its hits lying on the drawn surfaces and a short line along
# the surface's normal at each (screenshot viewer_surfaces.png).
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
        # each hit's normal: a line from the hit, the scene's normal length along the server's normal
        segments, length = browser.execute_script(
            "const r = %s.internals.rays, g = r.normals.geometry;"
            "return [Array.from(g.getAttribute('position').array.slice(0, 3 * g.drawRange.count)), r.normalLength]"
            % VIEWER)
        segments = np.array(segments).reshape(-1, 2, 3)
        assert len(segments) == 2 and length > 0
        np.testing.assert_allclose(segments[:, 0], hits.points[:2], atol=FLOAT32)
        np.testing.assert_allclose(segments[:, 1] - segments[:, 0], length * hits.normals[:2], atol=FLOAT32)
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        browser.save_screenshot(str(ARTIFACTS / "viewer_surfaces.png"))


def _sheet(rows, cols, cell):
    """(vertices, triangles) of a wavy sheet of (rows - 1) x (cols - 1) cells, two triangles each."""
    x, y = np.meshgrid((np.arange(cols) - (cols - 1) / 2) * cell, (np.arange(rows) - (rows - 1) / 2) * cell)
    v = np.stack([x, y, 0.3 * np.sin(x) * np.cos(0.7 * y)], -1).reshape(-1, 3)
    a = (np.arange(rows - 1)[:, None] * cols + np.arange(cols - 1)[None, :]).ravel()
    return v, np.stack([a, a + 1, a + cols + 1, a, a + cols + 1, a + cols], -1).reshape(-1, 3)


def _write_obj(path, vertices, triangles):
    with open(path, "w") as f:
        np.savetxt(f, vertices, fmt="v %.9g %.9g %.9g")
        np.savetxt(f, triangles + 1, fmt="f %d %d %d")


# Verifies that a 1,025 x 1,025 heightfield (a raw height map the server
# reads) and a 100,000-triangle mesh (an OBJ file) reach the page whole, as
# the binary arrays of the catalog message: the vertex and index counts of
# the drawn geometry are the grid's and the mesh's as the server stores
# them, and each object's world box is that of the posed samples and
# vertices within float32.
def test_a_million_sample_heightfield_and_a_100k_triangle_mesh_reach_the_page(server, browser, tmp_path):  # noqa: F811
    c = server.client
    c.set_gravity((0, 0, 0))
    rows = cols = 1025
    scale, offset, spacing = 3.0, -1.0, (0.05, 0.04)
    r, k = np.meshgrid(np.arange(rows), np.arange(cols), indexing="ij")
    samples = np.round(65535 * (0.5 + 0.5 * np.sin(k / 40.0) * np.cos(r / 57.0))).astype("<u2")
    (tmp_path / "terrain.raw").write_bytes(samples.tobytes())
    heights = offset + scale * samples[::-1].astype(np.float64) / 65535   # the file's first row is the grid's last
    field_q, field_p = _about_z(0.4), np.array([3.0, -2.0, -1.5])
    field = c.add_heightfield(str(tmp_path / "terrain.raw"), spacing, rows=rows, cols=cols, scale=scale,
                              offset=offset, position=field_p, orientation=field_q)
    vertices, triangles = _sheet(201, 251, 0.1)
    assert len(triangles) == 100_000
    _write_obj(tmp_path / "sheet.obj", vertices, triangles)
    mesh_q, mesh_p = _about_z(-0.7), np.array([-4.0, 1.0, 0.5])
    sheet = c.add_mesh(str(tmp_path / "sheet.obj"), position=mesh_p, orientation=mesh_q)
    c.snapshot(path=str(tmp_path / "world.snapshot"))
    stored = {b["id"]: b["shape"] for b in read_catalog(tmp_path / "world.snapshot")["bodies"]}
    assert stored[sheet]["vertices"].size == vertices.size and stored[sheet]["triangles"].size == triangles.size
    c.step(1)
    field_world = _grid(rows, cols, spacing, heights) @ _rotation(field_q).T + field_p
    mesh_world = stored[sheet]["vertices"].reshape(-1, 3) @ _rotation(mesh_q).T + mesh_p
    with ViewerProcess(["--lcm-url", server.url, "--prefix", server.prefix]) as viewer:
        open_page(browser, viewer.url, c.state().step)
        got = {b: _drawn(browser, b) for b in (field, sheet)}
        assert got[field]["vertices"] == rows * cols and got[field]["indices"] == 6 * (rows - 1) * (cols - 1)
        np.testing.assert_allclose(got[field]["box"], [field_world.min(0), field_world.max(0)], atol=FLOAT32)
        assert got[sheet]["vertices"] == len(vertices) and got[sheet]["indices"] == triangles.size
        np.testing.assert_allclose(got[sheet]["box"], [mesh_world.min(0), mesh_world.max(0)], atol=FLOAT32)
        assert browser.execute_script("return %s.surfaceErrors()" % VIEWER) == []


# Verifies that surfaces the page cannot draw (a snapshot file from
# elsewhere: a heightfield past the server's 2^24 samples, a mesh with an
# index past its vertices) are drawn as markers at their bodies' poses, and
# that the page says which bodies and why, in a replay of a recorded run.
def test_refused_surfaces_are_markers_with_their_reasons(server, browser, tmp_path):  # noqa: F811
    c = server.client
    c.set_gravity((0, 0, 0))
    ids = [c.add_sphere(0.1, position=(0, 0, 0)), c.add_sphere(0.1, position=(1, 0, 0))]
    assert ids == [1, 2]   # the snapshot below names these ids
    log_path = tmp_path / "run.lcmlog"
    with LcmRecorder(server.url, server.prefix + "_.*", log_path):
        c.step(2)
    damaged = tmp_path / "damaged.snapshot"
    damaged.write_bytes(snapshot(heightfield(4097, 4096, np.zeros(4)), mesh(TETRA, [[0, 1, 4]])))
    with ViewerProcess(["--log", str(log_path), "--snapshot", str(damaged)]) as viewer:
        open_page(browser, viewer.url)
        errors = browser.execute_script("return %s.surfaceErrors()" % VIEWER)
        assert errors == ["body 1 (s1): heightfield refused: 4097 x 4096 samples: more than the 16777216 a "
                          "heightfield may have", "body 2 (s2): mesh refused: index 4 out of range for 4 vertices"]
        assert browser.execute_script("return document.getElementById('message').textContent") == "\n".join(errors)
        markers = browser.execute_script(
            "const s = %s.internals.bodies.slots; return [1, 2].map((id) => s.get(id) && !s.get(id).object &&"
            " s.get(id).mesh.userData.ids.length)" % VIEWER)
        assert markers == [2, 2]   # both in the one instanced group of markers
        page = browser.execute_script("return %s.bodies()" % VIEWER)
        np.testing.assert_allclose([page["1"], page["2"]], [[0, 0, 0], [1, 0, 0]], atol=1e-9)
