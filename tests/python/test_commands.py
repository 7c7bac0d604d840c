"""Commands against the real server: step, reset, gravity, time step, forces,
impulses, pose, velocity, mass, material, contacts, callbacks."""
import numpy as np
import pytest

import contactsim

DEFAULT_DT = 1.0 / 240


def free_sphere(client, mass=2.0, radius=0.1, **kw):
    client.set_gravity((0, 0, 0))
    return client.add_sphere(radius, position=(0, 0, 5), mass=mass, **kw)


@pytest.mark.parametrize("n", [1, 7, 100])
def test_step_returns_with_the_state_of_its_last_step(client, n):
    start = client.step(1).step
    r = client.step(n)
    assert r.step == start + n
    st = client.state()
    assert st.step == r.step and st.time == r.time
    assert st.time == pytest.approx(r.step * DEFAULT_DT, rel=1e-12)


def test_on_state_sees_the_stepped_states(client):
    seen = []
    client.on_state(lambda s: seen.append(s.step))
    r = client.step(1)
    r2 = client.step(1)
    assert seen[-2:] == [r.step, r2.step]


def test_reset_keeps_method_and_paused_and_restores_defaults(client):
    client.set_contact_method("impulse", iterations=7)
    client.set_gravity((0, 0, -1))
    client.set_timestep(0.01)
    client.add_sphere(0.1)
    client.step(3)
    client.reset()
    st = client.wait_for_status(timeout=3.0)  # the next STATUS, sent after the reset
    assert st.paused and st.method == "impulse" and "iterations=7" in st.method_params.split()
    assert (st.step, st.time, st.num_bodies, st.dt) == (0, 0.0, 0, pytest.approx(DEFAULT_DT, rel=1e-12))
    r = client.step(1)
    s = client.state()
    assert (r.step, s.step, len(s.bodies)) == (1, 1, 0)
    assert s.time == pytest.approx(DEFAULT_DT, rel=1e-12)
    ball = client.add_sphere(0.1, position=(0, 0, 10))
    client.step(1)
    vz = client.state().bodies[ball].linear_velocity[2]
    assert vz == pytest.approx(-9.81 * DEFAULT_DT, rel=1e-12)  # default gravity again


def test_reset_keeps_running(client):
    client.resume()
    client.reset()
    st = client.wait_for_status(timeout=3.0)
    assert not st.paused
    later = client.wait_for_state(lambda s: s.step > 10, timeout=3.0)
    assert later.step > 10
    client.pause()


def test_set_gravity(client):
    client.set_gravity((1.0, 2.0, -3.0))
    ball = client.add_sphere(0.1, position=(0, 0, 100))
    r = client.step(10)
    v = client.state().bodies[ball].linear_velocity
    np.testing.assert_allclose(v, np.array([1.0, 2.0, -3.0]) * r.time, rtol=1e-12)


def test_set_timestep(client):
    client.set_timestep(0.002)
    r = client.step(5)
    assert r.time == pytest.approx(0.01, rel=1e-12)
    assert client.wait_for_status(timeout=3.0).dt == 0.002


@pytest.mark.parametrize("dt,duration", [(1.0 / 256, 0.125), (DEFAULT_DT, 0.1), (0.01, 0.07)])
def test_force_for_a_duration_gives_f_over_m_times_duration(client, dt, duration):
    client.set_timestep(dt)
    ball = free_sphere(client, mass=2.0)
    force = np.array([4.0, -2.0, 1.0])
    client.apply_force(ball, force, duration=duration)
    client.step(int(round(duration / dt)) + 20)
    v = client.state().bodies[ball].linear_velocity
    np.testing.assert_allclose(v, force / 2.0 * duration, rtol=0, atol=1e-6)


def test_force_with_zero_duration_acts_for_one_step(client):
    ball = free_sphere(client, mass=2.0)
    client.apply_force(ball, (4.0, 0, 0))
    client.step(5)
    v = client.state().bodies[ball].linear_velocity
    np.testing.assert_allclose(v, [2.0 * DEFAULT_DT, 0, 0], rtol=0, atol=1e-12)


def test_torque_for_a_duration(client):
    client.set_timestep(1.0 / 256)
    ball = free_sphere(client, mass=2.0, radius=0.1)  # I = 2/5 m r^2 = 0.008
    client.apply_force(ball, (0, 0, 0), torque=(0, 0, 0.016), duration=0.125)
    client.step(60)
    w = client.state().bodies[ball].angular_velocity
    np.testing.assert_allclose(w, [0, 0, 0.016 / 0.008 * 0.125], rtol=0, atol=1e-6)


def test_impulse_at_the_centre_gives_j_over_m_exactly(client):
    ball = free_sphere(client, mass=2.0)
    client.apply_impulse(ball, (1.0, -0.5, 0.25))
    client.step(1)
    b = client.state().bodies[ball]
    assert list(b.linear_velocity) == [0.5, -0.25, 0.125]
    assert list(b.angular_velocity) == [0.0, 0.0, 0.0]


def test_impulse_at_a_point_spins(client):
    ball = free_sphere(client, mass=2.0, radius=0.1)  # I = 0.008
    client.apply_impulse(ball, (1.0, 0, 0), point=(0, 0, 5.1))  # r = (0, 0, 0.1) from the centre
    client.step(1)
    b = client.state().bodies[ball]
    np.testing.assert_allclose(b.linear_velocity, [0.5, 0, 0], atol=1e-12)
    np.testing.assert_allclose(b.angular_velocity, [0, 0.1 / 0.008, 0], rtol=1e-9)


def test_pose_velocity_mass_material_remove(client):
    ball = free_sphere(client, mass=2.0)
    other = client.add_box((0.1, 0.1, 0.1), position=(3, 0, 5))
    client.set_pose(ball, (1, 2, 3), (2, 0, 0, 0))  # normalised by the server
    client.set_velocity(ball, (0.5, 0, 0), (0, 0, 1))
    client.step(1)
    b = client.state().bodies[ball]
    np.testing.assert_allclose(b.position, [1 + 0.5 * DEFAULT_DT, 2, 3], atol=1e-12)
    np.testing.assert_allclose(b.orientation[0], np.cos(0.5 * DEFAULT_DT), atol=1e-9)
    client.set_mass(ball, mass=4.0)
    client.set_velocity(ball, (0, 0, 0), (0, 0, 0))
    client.apply_impulse(ball, (1.0, 0, 0))
    client.step(1)
    assert client.state().bodies[ball].linear_velocity[0] == 0.25
    client.set_material(ball, restitution=0.9, friction=0.1)
    client.remove_body(other)
    client.step(1)
    assert list(client.state().bodies) == [ball]


def test_contacts_of_a_resting_sphere(client):
    plane = client.add_plane((0, 0, 1), 0.0)
    ball = client.add_sphere(0.1, position=(0, 0, 0.1))
    client.step(40)
    cs = client.contacts()
    assert cs.method == "impulse" and cs.value_kind == "impulse" and cs.step > 0
    mine = [c for c in cs if {c.body_a, c.body_b} == {plane, ball}]
    assert mine, "no plane-ball contact in %r" % (cs,)
    for c in mine:
        up = c.normal if c.body_a == plane else -c.normal  # normal points from a to b
        np.testing.assert_allclose(up, [0, 0, 1], atol=1e-9)
        assert abs(c.point[2]) < 2e-3 and c.depth < 2e-3


def test_status_fields(client):
    st = client.wait_for_server()
    assert st.version and st.mode == "free_run" and st.paused and st.method == "impulse"
    client.set_mode("realtime", real_time_factor=2.0)
    st = client.wait_for_status(lambda s: s.mode == "realtime", timeout=3.0)
    assert st.target_real_time_factor == 2.0
