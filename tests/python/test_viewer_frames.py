"""The viewer bridge's readers without a browser: STATE and CONTACTS read
with numpy equal LCM's generated decoders, and a real server's snapshot
file gives every shape, mass and joint (docs/viewer.md)."""
import numpy as np
import pytest

import contactsim
from contactsim.viewer.catalog import read_catalog
from contactsim.viewer.frames import contacts_frame, contacts_from_payload, poses_frame, read_state


def _state(n, rng):
    m = contactsim.state_t()
    m.time, m.step, m.kinetic_energy, m.potential_energy = 1.25, 300, 2.5, -7.0
    for i in range(n):
        b = contactsim.body_state_t()
        b.id = 3 * i + 1
        b.position, b.orientation = list(rng.normal(size=3)), list(rng.normal(size=4))
        b.linear_velocity, b.angular_velocity = list(rng.normal(size=3)), list(rng.normal(size=3))
        m.bodies.append(b)
    m.num_bodies = n
    return m


# Verifies that read_state gives the generated decoder's numbers and refuses
# a payload that is not exactly one state_t.
def test_read_state_matches_lcm_decoding():
    m = _state(50, np.random.default_rng(3))
    payload = m.encode()
    head, bodies = read_state(payload)
    assert (head["step"], head["time"], head["n"]) == (300, 1.25, 50)
    np.testing.assert_array_equal(bodies["id"], [b.id for b in m.bodies])
    np.testing.assert_array_equal(bodies["x"], [b.position for b in m.bodies])
    np.testing.assert_array_equal(bodies["q"], [b.orientation for b in m.bodies])
    assert read_state(payload[:-1]) is None and read_state(payload + b"\0") is None
    assert read_state(contactsim.status_t().encode()) is None
    frame = np.frombuffer(poses_frame(300, 1.25, 2.5, -7.0, bodies["id"], bodies["x"], bodies["q"]), "<f8")
    assert list(frame[:6]) == [1, 300, 1.25, 2.5, -7.0, 50]


# Verifies that a STATE with a joint block reads the same bodies, and that a
# payload cut inside the block is refused.
def test_read_state_reads_past_the_joints():
    m = _state(4, np.random.default_rng(5))
    m.num_joints = 3
    m.joint_ids, m.joint_model_ids = [7, 8, 9], [1, 1, 0]
    m.joint_positions, m.joint_velocities, m.joint_efforts = [0.1, 0.2, 0.3], [1.0, 2.0, 3.0], [4.0, 5.0, 6.0]
    payload = m.encode()
    head, bodies = read_state(payload)
    assert head["n"] == 4
    np.testing.assert_array_equal(bodies["x"], [b.position for b in m.bodies])
    assert read_state(payload[:-8]) is None


# Verifies that contacts_from_payload reads points and normals past the
# method string, whatever its length.
def test_contacts_payload_matches_lcm_decoding():
    rng = np.random.default_rng(5)
    for method in ("", "impulse", "a-much-longer-method-name"):
        m = contactsim.contacts_t()
        m.step, m.method, m.value_kind = 12, method, contactsim.contacts_t.FORCE
        for _ in range(7):
            c = contactsim.contact_t()
            c.point, c.normal, c.tangent_value = list(rng.normal(size=3)), list(rng.normal(size=3)), [0.0] * 3
            m.contacts.append(c)
        m.num_contacts = 7
        assert contacts_from_payload(m.encode()) == contacts_frame(12, [c.point for c in m.contacts],
                                                                   [c.normal for c in m.contacts])
        assert contacts_from_payload(m.encode()[:-3]) is None


# Verifies that a real server's snapshot file names every body's shape,
# motion and mass, and the joints with their anchors.
def test_catalog_from_server_snapshot(client, tmp_path):
    client.add_plane((0, 0, 1), 0.5)
    ball = client.add_sphere(0.2, position=(0, 0, 1), mass=3.0)
    box = client.add_box((0.1, 0.2, 0.3), position=(1, 0, 1), fixed=True)
    client.add_capsule(0.1, 0.4, position=(2, 0, 1))
    client.add_convex([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], position=(3, 0, 1))
    client.add_joint("distance", ball, None, anchor=(0, 0, 2))
    path = tmp_path / "catalog.snapshot"
    client.snapshot(path=str(path))
    cat = read_catalog(path)
    shapes = {b["id"]: b["shape"] for b in cat["bodies"]}
    assert [s["kind"] for s in shapes.values()] == ["plane", "sphere", "box", "capsule", "convex"]
    assert shapes[1]["normal"] == [0, 0, 1] and shapes[1]["offset"] == 0.5
    assert shapes[ball]["radius"] == 0.2 and shapes[box]["half_extents"] == [0.1, 0.2, 0.3]
    assert shapes[4]["half_length"] == 0.4 and len(shapes[5]["faces"]) == 4
    by_id = {b["id"]: b for b in cat["bodies"]}
    assert by_id[ball]["mass"] == 3.0 and by_id[box]["motion"] == "static"
    assert by_id[ball]["x"] == [0, 0, 1]
    (joint,) = cat["joints"]
    assert (joint["kind"], joint["body_a"], joint["body_b"], joint["anchor_b"]) == ("distance", ball, 0, [0, 0, 2])


# Verifies that the bridge refuses a WebSocket opened by a page of another
# origin (any web site in the user's browser) and accepts its own page's.
def test_websocket_refuses_other_origins():
    import asyncio

    import aiohttp
    from aiohttp.test_utils import TestClient, TestServer

    from contactsim.viewer.server import make_app

    class Source:
        mode, catalog, catalog_version = "replay", {"bodies": [], "joints": []}, 1

        def hello(self):
            return {"type": "hello", "mode": "replay"}

    async def run():
        async with TestClient(TestServer(make_app(Source()))) as tc:
            with pytest.raises(aiohttp.WSServerHandshakeError):
                await tc.ws_connect("/ws", headers={"Origin": "http://evil.example"})
            own = "http://%s:%d" % (tc.host, tc.port)
            async with tc.ws_connect("/ws", headers={"Origin": own}) as ws:
                assert (await ws.receive_json())["type"] == "hello"
    asyncio.run(run())


def _urdf_visuals(path):
    """{link: [(mesh file or None, rgba)]} of a URDF's visual elements, read with ElementTree."""
    import os
    import xml.etree.ElementTree as ET
    root = ET.parse(path).getroot()
    colours = {m.get("name"): [float(x) for x in m.find("color").get("rgba").split()]
               for m in root.findall("material") if m.find("color") is not None}
    out = {}
    for link in root.findall("link"):
        out[link.get("name")] = []
        for v in link.findall("visual"):
            mesh = v.find("geometry/mesh")
            file = os.path.join(os.path.dirname(path), mesh.get("filename")) if mesh is not None else None
            m = v.find("material")
            out[link.get("name")].append((file, colours.get(m.get("name")) if m is not None else None))
    return out


# Verifies that a real server's snapshot keeps every link's visual elements
# (the resolved mesh file, the material's colour) and the compound bodies'
# children, and that each mesh gets a URL of its folder.
def test_catalog_keeps_the_models_visuals(launch, tmp_path):
    import os
    pybullet_data = pytest.importorskip("pybullet_data")
    from contactsim.viewer.meshes import MeshFiles
    iiwa_path = os.path.join(pybullet_data.getDataPath(), "kuka_iiwa", "model.urdf")
    c = launch(args=("--model-path", pybullet_data.getDataPath())).client
    iiwa = c.load_model(iiwa_path, name="iiwa", fixed_base=True)
    path = tmp_path / "models.snapshot"
    c.snapshot(path=str(path))
    cat = read_catalog(path)
    (model,) = cat["models"]
    assert model["name"] == "iiwa" and [l["name"] for l in model["links"]] == iiwa.links
    expected = _urdf_visuals(iiwa_path)
    for link in model["links"]:
        want = expected[link["name"]]
        assert [os.path.realpath(v["mesh_path"]) for v in link["visuals"]] == \
            [os.path.realpath(f) for f, _ in want], link["name"]
        # urdfdom keeps colours as floats
        np.testing.assert_allclose([v["rgba"] for v in link["visuals"]], [rgba for _, rgba in want], atol=1e-7)
        assert link["body"] == iiwa.body_id(link["name"])
    kinds = {b["id"]: b["shape"]["kind"] for b in cat["bodies"]}
    assert {kinds[l["body"]] for l in model["links"]} == {"compound"}
    children = next(b for b in cat["bodies"] if b["id"] == model["links"][1]["body"])["shape"]["children"]
    assert children and children[0]["shape"]["kind"] == "convex" and len(children[0]["orientation"]) == 4
    hinges = {j["id"]: j for j in cat["joints"]}
    assert [hinges[j["joint"]]["kind"] for j in model["joints"]] == ["hinge"] * 7
    meshes = MeshFiles()
    meshes.add_urls(cat)
    urls = [v["url"] for l in model["links"] for v in l["visuals"]]
    assert urls == ["/meshes/0/link_%d.obj" % i for i in range(8)]
    assert meshes.resolve("0", "link_3.obj") == os.path.realpath(model["links"][3]["visuals"][0]["mesh_path"])


def _mesh_folder(tmp_path):
    """A model folder with a served mesh, and beside it what must not be served."""
    meshes = tmp_path / "robot" / "meshes"
    meshes.mkdir(parents=True)
    (meshes / "arm.stl").write_bytes(b"solid arm\nendsolid arm\n")
    (meshes / "notes.txt").write_text("not a mesh")
    (tmp_path / "robot" / "secret.stl").write_text("outside the mesh folder")
    (meshes / "escape.stl").symlink_to(tmp_path / "robot" / "secret.stl")
    catalog = {"models": [{"links": [{"visuals": [{"kind": "mesh", "mesh_path": str(meshes / "arm.stl")}]}]}]}
    return catalog


# Verifies that the bridge serves a model's mesh file and refuses every
# request that leaves the mesh's folder (.., encoded or not, an absolute
# path, a symbolic link out of it), names no model's folder, or asks for a
# file that is not a mesh, material or texture.
def test_mesh_requests_outside_the_models_folders_are_refused(tmp_path):
    import asyncio

    from aiohttp.test_utils import TestClient, TestServer

    from contactsim.viewer.meshes import MeshFiles
    from contactsim.viewer.server import make_app

    class Source:
        mode, catalog_version = "replay", 1

        def __init__(self):
            self.catalog = _mesh_folder(tmp_path)
            self.meshes = MeshFiles()
            self.meshes.add_urls(self.catalog)

    source = Source()
    url = source.catalog["models"][0]["links"][0]["visuals"][0]["url"]
    assert url == "/meshes/0/arm.stl"
    refused = ["/meshes/0/..%2Fsecret.stl", "/meshes/0/%2E%2E/secret.stl", "/meshes/0/%2E%2E%2Fsecret.stl",
               "/meshes/0/escape.stl", "/meshes/0/notes.txt", "/meshes/0/%2Fetc%2Fpasswd",
               "/meshes/0/..%2F..%2F..%2F..%2F..%2F..%2Fetc%2Fpasswd", "/meshes/1/arm.stl", "/meshes/x/arm.stl",
               "/meshes/-1/arm.stl", "/meshes/0/", "/meshes/0/arm.stl%00.stl"]

    async def run():
        async with TestClient(TestServer(make_app(source))) as tc:
            ok = await tc.get(url)
            assert ok.status == 200 and await ok.read() == b"solid arm\nendsolid arm\n"
            for bad in refused:
                r = await tc.get(bad)
                assert r.status in (403, 404), (bad, r.status)
                assert b"outside" not in await r.read(), bad
    asyncio.run(run())
    for folder, relative in [("0", "../secret.stl"), ("0", str(tmp_path / "robot" / "secret.stl")),
                             ("0", "escape.stl"), ("0", "notes.txt"), ("1", "arm.stl")]:
        assert source.meshes.resolve(folder, relative) is None, relative
