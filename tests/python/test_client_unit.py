"""The client against a pure-Python fake server: encoding, reply matching,
errors, timeouts and waits. No contactsim-server binary needed."""
import math
import time

import numpy as np
import pytest

import contactsim
from contactsim import body_cmd_t, scene_cmd_t


def test_add_sphere_encodes_every_field(fake_server, fake_client):
    bid = fake_client.add_sphere(0.25, position=np.array([1, 2, 3]), mass=2.0,
                                 orientation=[0, 1, 0, 0], velocity=(0.5, 0, 0),
                                 angular_velocity=(0, 0, 3), restitution=0.7, fixed=True,
                                 name="ball")
    assert bid == 1
    m = fake_server.commands[-1]
    assert (m.op, m.shape, m.radius, m.mass, m.density) == (body_cmd_t.ADD, body_cmd_t.SPHERE, 0.25, 2.0, 0.0)
    assert list(m.position) == [1, 2, 3] and list(m.orientation) == [0, 1, 0, 0]
    assert list(m.linear_velocity) == [0.5, 0, 0] and list(m.angular_velocity) == [0, 0, 3]
    assert m.has_restitution and m.restitution == 0.7 and not m.has_friction
    assert m.fixed and m.name == "ball" and m.client_id == fake_client.client_id


def test_defaults_leave_material_and_mass_to_the_server(fake_server, fake_client):
    fake_client.add_box((0.1, 0.2, 0.3))
    m = fake_server.commands[-1]
    assert (m.shape, list(m.half_extents)) == (body_cmd_t.BOX, [0.1, 0.2, 0.3])
    assert (m.mass, m.density, m.has_restitution, m.has_friction, m.fixed) == (0, 0, False, False, False)
    assert list(m.orientation) == [1, 0, 0, 0]


def test_other_shapes_and_body_ops(fake_server, fake_client):
    c = fake_client
    c.add_capsule(0.1, 0.5, density=500)
    assert (fake_server.commands[-1].shape, fake_server.commands[-1].half_length) == (body_cmd_t.CAPSULE, 0.5)
    c.add_convex([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    m = fake_server.commands[-1]
    assert m.shape == body_cmd_t.CONVEX and m.num_points == 4 and list(m.points[3]) == [0, 0, 1]
    c.add_plane((0, 0, 2), 0.5, friction=0.3)
    m = fake_server.commands[-1]
    assert (m.shape, list(m.plane_normal), m.plane_offset, m.has_friction) == (body_cmd_t.PLANE, [0, 0, 2], 0.5, True)
    c.remove_body(7)
    assert (fake_server.commands[-1].op, fake_server.commands[-1].body_id) == (body_cmd_t.REMOVE, 7)
    c.set_pose(3, (1, 1, 1), (1, 0, 0, 0))
    c.set_velocity(3, (1, 0, 0), (0, 0, 1))
    c.apply_force(3, (0, 0, 10), duration=0.5)
    m = fake_server.commands[-1]
    assert (m.op, list(m.force), list(m.torque), m.duration) == (body_cmd_t.APPLY_FORCE, [0, 0, 10], [0, 0, 0], 0.5)
    c.apply_impulse(3, (1, 0, 0))
    assert not fake_server.commands[-1].has_point
    c.apply_impulse(3, (1, 0, 0), point=(0, 0, 1))
    assert fake_server.commands[-1].has_point and list(fake_server.commands[-1].point) == [0, 0, 1]
    c.set_mass(3, density=200)
    assert (fake_server.commands[-1].mass, fake_server.commands[-1].density) == (0, 200)
    c.set_material(3, restitution=0.1)
    m = fake_server.commands[-1]
    assert (m.op, m.has_restitution, m.restitution, m.has_friction) == (body_cmd_t.SET_MATERIAL, True, 0.1, False)


def test_collision_filters_are_encoded_as_the_wires_bit_patterns(fake_server, fake_client):
    c = fake_client
    c.add_box((0.1, 0.1, 0.1))
    m = fake_server.commands[-1]
    assert (m.has_filter, m.collision_category, m.collision_mask, m.collision_group) == (False, 1, -1, 0)
    c.add_sphere(0.1, collision_category=0x80000000, collision_group=-4)
    m = fake_server.commands[-1]
    assert (m.has_filter, m.collision_category, m.collision_mask, m.collision_group) == (True, -(1 << 31), -1, -4)
    c.add_plane((0, 0, 1), 0.0, collision_mask=6)
    assert (fake_server.commands[-1].has_filter, fake_server.commands[-1].collision_mask) == (True, 6)
    c.set_filter(3, collision_category=2, collision_mask=0xFFFFFFFE, collision_group=5)
    m = fake_server.commands[-1]
    assert (m.op, m.body_id, m.collision_category, m.collision_mask, m.collision_group) == (
        body_cmd_t.SET_FILTER, 3, 2, -2, 5)
    c.set_filter(3)
    m = fake_server.commands[-1]
    assert (m.collision_category, m.collision_mask, m.collision_group) == (1, -1, 0)


def test_scene_commands(fake_server, fake_client):
    c = fake_client
    c.reset()
    c.load_scene("/tmp/x.pbtxt")
    assert fake_server.commands[-1].path == "/tmp/x.pbtxt"
    c.set_gravity((0, 0, -1.62))
    c.set_timestep(0.002)
    assert fake_server.commands[-1].dt == 0.002
    c.set_contact_method("lcp", solver="pgs", iterations=50, tolerance=1e-7, warm_start=True)
    m = fake_server.commands[-1]
    assert m.op == scene_cmd_t.SET_METHOD and m.method == "lcp" and m.num_params == 4
    assert dict(zip(m.param_names, m.param_values)) == {
        "solver": "pgs", "iterations": "50", "tolerance": "1e-07", "warm_start": "true"}
    c.set_mode("realtime", real_time_factor=0.5)
    assert (fake_server.commands[-1].mode, fake_server.commands[-1].real_time_factor) == (scene_cmd_t.REALTIME, 0.5)
    c.set_mode("free_run")
    assert fake_server.commands[-1].mode == scene_cmd_t.FREE_RUN
    c.pause()
    c.resume()
    assert [m.op for m in fake_server.commands[-2:]] == [scene_cmd_t.PAUSE, scene_cmd_t.RESUME]
    ids = [m.request_id for m in fake_server.commands]
    assert ids == list(range(1, len(ids) + 1))


def test_shapes_are_checked_before_sending(fake_server, fake_client):
    with pytest.raises(ValueError, match="position"):
        fake_client.add_sphere(0.1, position=(0, 0))
    with pytest.raises(ValueError, match="orientation"):
        fake_client.set_pose(1, (0, 0, 0), (1, 0, 0))
    with pytest.raises(ValueError, match="points"):
        fake_client.add_convex([0, 0, 1])
    with pytest.raises(ValueError, match="mode"):
        fake_client.set_mode("fast")
    assert fake_server.commands == []


def test_values_are_not_validated_by_the_client(fake_server, fake_client):
    fake_client.add_sphere(-1.0, position=(math.nan, math.inf, 0), mass=1, density=2)
    m = fake_server.commands[-1]
    assert m.radius == -1.0 and math.isnan(m.position[0]) and math.isinf(m.position[1])
    assert (m.mass, m.density) == (1, 2)


def test_error_reply_raises_command_error(fake_server, fake_client):
    fake_server.behaviour = lambda m: (1, "radius must be a finite number > 0, got -1")
    with pytest.raises(contactsim.CommandError) as e:
        fake_client.add_sphere(-1)
    assert e.value.code == contactsim.reply_t.INVALID_ARGUMENT
    assert e.value.code_name == "INVALID_ARGUMENT"
    assert e.value.message == "radius must be a finite number > 0, got -1"
    assert "radius" in str(e.value)
    assert not isinstance(e.value, contactsim.TimeoutError)


def test_replies_to_other_clients_are_ignored(fake_server, fake_client):
    fake_server.decoy = True
    assert fake_client.add_sphere(0.1) == 1


def test_no_reply_raises_timeout(fake_server):
    fake_server.silent = True
    with contactsim.Client(url=fake_server.url, prefix=fake_server.prefix, timeout=0.2) as c:
        t0 = time.monotonic()
        with pytest.raises(contactsim.TimeoutError) as e:
            c.reset()
        assert time.monotonic() - t0 < 1.5
        assert isinstance(e.value, TimeoutError) and isinstance(e.value, contactsim.CommandError)
        assert e.value.code is None and "reply" in str(e.value)


def test_step_returns_with_the_state_of_the_last_step(fake_server, fake_client):
    r = fake_client.step(5)
    assert r.step == 5 and fake_client.state().step == 5
    fake_server.reply_before_state, fake_server.state_delay = True, 0.3
    r = fake_client.step(3)
    assert r.step == 8 and fake_client.state().step == 8


def test_step_without_its_state_times_out(fake_server):
    fake_server.reply_before_state, fake_server.state_delay = True, 1.0
    with contactsim.Client(url=fake_server.url, prefix=fake_server.prefix, timeout=0.3) as c:
        with pytest.raises(contactsim.TimeoutError, match="STATE"):
            c.step(1)


def test_state_waits_and_callbacks(fake_server, fake_client):
    assert fake_client.state() is None and len(fake_client.contacts()) == 0
    seen = []
    remove = fake_client.on_state(lambda s: seen.append(s.step))
    fake_server.publish_state(1)
    assert fake_client.wait_for_state(lambda s: s.step >= 1).step == 1
    b = contactsim.body_state_t()
    b.id, b.position, b.orientation = 4, [0.0, 0.0, 2.0], [1.0, 0.0, 0.0, 0.0]
    for k in (2, 3, 4):
        fake_server.publish_state(k, [b])
    st = fake_client.wait_for_state(lambda s: s.step == 4)
    assert st.bodies[4].position[2] == 2.0
    remove()
    assert seen[:4] == [1, 2, 3, 4]
    with pytest.raises(contactsim.TimeoutError):
        fake_client.wait_for_state(lambda s: s.step == 99, timeout=0.2)


def test_status_and_wait_for_server(fake_server, fake_client):
    assert fake_client.status() is None
    with pytest.raises(contactsim.TimeoutError):
        fake_client.wait_for_server(timeout=0.1)
    fake_server.publish_status(paused=True, method="impulse", num_bodies=3)
    st = fake_client.wait_for_server(timeout=2)
    assert st.paused and st.method == "impulse" and st.mode == "free_run" and st["num_bodies"] == 3
    assert fake_client.status().as_dict()["version"] == "fake"


def test_status_parses_the_method_contract(fake_server, fake_client):
    # Verifies that Status.contract() turns STATUS's method_contract text
    # into booleans and the friction words, and is empty when there is none.
    fake_server.publish_status(method="barrier", method_contract=(
        "joints=no; restitution=no; kinematic=yes; friction=regularized: smoothed coulomb disk, lagged (eps_v)"))
    st = fake_client.wait_for_status(lambda s: s.method == "barrier", timeout=2)
    assert st.contract() == {"joints": False, "restitution": False, "kinematic": True,
                             "friction": "regularized: smoothed coulomb disk, lagged (eps_v)"}
    fake_server.publish_status(method="old")
    assert fake_client.wait_for_status(lambda s: s.method == "old", timeout=2).contract() == {}


def test_commands_inside_callbacks_are_refused(fake_server, fake_client):
    errors = []

    def cb(state):
        try:
            fake_client.reset()
        except RuntimeError as e:
            errors.append(e)
    fake_client.on_state(cb)
    fake_server.publish_state(1)
    fake_client.wait_for_state(lambda s: s.step >= 1)
    deadline = time.monotonic() + 2.0
    while not errors and time.monotonic() < deadline:
        time.sleep(0.01)
    assert errors and "callback" in str(errors[0])


def test_default_url(monkeypatch):
    monkeypatch.delenv("LCM_DEFAULT_URL", raising=False)
    assert contactsim.default_url() == "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608"
    monkeypatch.setenv("LCM_DEFAULT_URL", "udpm://239.255.76.67:7999?ttl=0")
    assert contactsim.default_url() == "udpm://239.255.76.67:7999?ttl=0"
