"""Kinematic bodies through the real server: infinite mass, moved only by their
own velocity. They carry and push dynamic bodies and are never pushed back."""
import numpy as np
import pytest

from contactsim import reply_t
from contactsim.errors import CommandError

R = 0.1          # m, sphere radius
THICK = 0.05     # m, platform half thickness


def test_platform_moves_with_its_velocity_and_lifts_a_sphere(client):
    v = 0.5  # m/s up
    platform = client.add_box((0.5, 0.5, THICK), position=(0, 0, 0), velocity=(0, 0, v), kinematic=True)
    ball = client.add_sphere(R, position=(0, 0, THICK + R), restitution=0.0)
    r = client.step(240)
    t = r.time
    s = client.state().bodies
    # x = x0 + v t exactly (up to the clock's round-off): gravity and the
    # sphere's weight do not act on it
    np.testing.assert_allclose(s[platform].position, [0, 0, v * t], atol=1e-9)
    np.testing.assert_allclose(s[platform].linear_velocity, [0, 0, v], atol=1e-12)
    # the sphere rides on top, rising with it
    assert s[ball].position[2] == pytest.approx(v * t + THICK + R, abs=2e-3)
    assert s[ball].linear_velocity[2] == pytest.approx(v, abs=1e-2)


def test_set_velocity_steers_and_force_is_refused(client):
    platform = client.add_box((0.5, 0.5, THICK), kinematic=True)
    client.set_velocity(platform, (1.0, 0, 0), (0, 0, 0))
    r = client.step(120)
    assert client.state().bodies[platform].position[0] == pytest.approx(r.time, abs=1e-9)
    with pytest.raises(CommandError) as err:
        client.apply_force(platform, (0, 0, 100.0))
    assert err.value.code == reply_t.FAILED_PRECONDITION and "kinematic" in str(err.value)


@pytest.mark.parametrize("e", [0.0, 0.5])
def test_moving_wall_hits_a_box_like_an_infinite_mass(client, e):
    client.add_plane((0, 0, 1), 0.0, friction=0.0)
    wall = client.add_box((0.05, 0.5, 0.5), position=(-0.5, 0, 0.5), velocity=(1.0, 0, 0), kinematic=True,
                          restitution=e, friction=0.0)
    box = client.add_box((0.1, 0.1, 0.1), position=(0, 0, 0.1), restitution=e, friction=0.0)
    client.step(480)  # 2 s: the wall meets the box after 0.35 s
    s = client.state().bodies
    assert s[wall].linear_velocity[0] == pytest.approx(1.0, abs=1e-12)
    # Newton's law against an infinite mass: the box leaves at (1 + e) times
    # the wall's speed, ahead of its face
    assert s[box].position[0] >= s[wall].position[0] + 0.05 + 0.1 - 2e-3
    assert s[box].linear_velocity[0] == pytest.approx(1.0 + e, abs=1e-2)
