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
