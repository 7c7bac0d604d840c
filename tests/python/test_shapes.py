"""Capsules and convex hulls through the real server: added, simulated, validated."""
import numpy as np
import pytest

import contactsim


def test_capsule_falls_and_rests_on_its_side(client):
    client.add_plane((0, 0, 1), 0.0, restitution=0.0, friction=0.8)
    # axis tilted 80 degrees from vertical, so it topples and lies down
    angle = np.radians(80.0)
    q = (np.cos(angle / 2), np.sin(angle / 2), 0.0, 0.0)
    cap = client.add_capsule(0.05, 0.2, position=(0, 0, 0.3), orientation=q, restitution=0.0, friction=0.8)
    client.step(1200)
    body = client.state().bodies[cap]
    # lying flat: the centre is one radius above the plane, within the slop
    assert body.position[2] == pytest.approx(0.05, abs=2e-3)
    assert np.linalg.norm(body.linear_velocity) < 1e-2


def test_convex_hull_of_a_cube_cloud_rests_like_a_box(client):
    client.add_plane((0, 0, 1), 0.0, restitution=0.0)
    corners = [(x, y, z) for x in (-0.1, 0.1) for y in (-0.1, 0.1) for z in (-0.1, 0.1)]
    interior = [(0.0, 0.0, 0.0), (0.05, -0.02, 0.01)]  # not on the hull
    hull = client.add_convex(corners + interior, position=(0, 0, 0.5), restitution=0.0)
    client.step(960)
    body = client.state().bodies[hull]
    assert body.position[2] == pytest.approx(0.1, abs=2e-3)


@pytest.mark.parametrize("points, says", [
    ([(0, 0, 0), (1, 0, 0), (0, 1, 0)], "at least 4 points"),
    ([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)], "coplanar"),
    ([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, float("nan"))], "finite"),
])
def test_bad_convex_point_clouds_are_rejected(client, points, says):
    before = client.step(1)
    hash_before = client.state().state_hash
    with pytest.raises(contactsim.CommandError) as err:
        client.add_convex(points, position=(0, 0, 1))
    assert says in str(err.value)
    client.step(1)
    assert len(client.state().bodies) == 0
    assert before.step + 1 == client.state().step
    assert hash_before != 0


@pytest.mark.parametrize("radius, half_length, says", [
    (-0.1, 0.2, "radius"),
    (0.0, 0.2, "radius"),
    (0.1, -0.2, "half_length"),
])
def test_degenerate_capsules_are_rejected(client, radius, half_length, says):
    with pytest.raises(contactsim.CommandError) as err:
        client.add_capsule(radius, half_length, position=(0, 0, 1))
    assert says in str(err.value)
