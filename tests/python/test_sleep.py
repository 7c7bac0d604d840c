"""Sleeping through the real server (docs/physics.md, "Sleeping"): on by
default, counted in STATUS, and woken by every command on a sleeping body."""
import pytest

HALF = 0.1            # m, the box
MASS = 8.0            # kg: a 0.2 m cube at the default 1000 kg/m^3
STATUS_WAIT = 5.0     # s of wall-clock time: STATUS comes at 1 Hz


def test_a_resting_box_sleeps_keeps_its_pose_and_wakes_on_an_impulse(client):
    client.add_plane((0, 0, 1), 0.0)
    box = client.add_box((HALF, HALF, HALF), position=(0, 0, HALF + 0.01), restitution=0.0)
    client.step(480)  # settles within 0.2 s, then 0.5 s below the thresholds
    status = client.wait_for_status(lambda s: s.num_sleeping == 1, timeout=STATUS_WAIT)
    assert status.num_bodies == 2
    slept = client.state().bodies[box]
    client.step(240)
    now = client.state().bodies[box]
    # asleep: not stepped, so bit for bit where it slept
    assert list(now.position) == list(slept.position)
    assert list(now.orientation) == list(slept.orientation)
    assert list(now.linear_velocity) == [0.0, 0.0, 0.0]
    # an impulse wakes it and acts at the next step: 1 m/s up
    client.apply_impulse(box, (0, 0, MASS * 1.0))
    client.step(1)
    assert client.state().bodies[box].linear_velocity[2] == pytest.approx(1.0 - 9.81 / 240, abs=0.02)
    client.wait_for_status(lambda s: s.num_sleeping == 0, timeout=STATUS_WAIT)
