"""Compound bodies and explicit mass properties through the real server:
added, simulated, kept by snapshots, refused where a method cannot take them."""
import numpy as np
import pytest

import contactsim

TABLE = [{"shape": "box", "half_extents": (0.2, 0.15, 0.015), "position": (0, 0, 0.2)}] + [
    {"shape": "box", "half_extents": (0.015, 0.015, 0.1), "position": (0.17 * sx, 0.12 * sy, 0.085)}
    for sx in (-1, 1) for sy in (-1, 1)]


def test_table_of_five_boxes_stands_on_its_legs(client):
    client.add_plane((0, 0, 1), 0.0)
    table = client.add_compound(TABLE, position=(0, 0, 0.02), mass=3.0)
    client.step(480)
    body = client.state().bodies[table]
    # the frame's origin rests 0.015 m up; the centre of mass is above it by
    # the parts' first moment: (0.4 * 0.3 * 0.03 * 0.2 + 4 * 0.03^2 * 0.2 * 0.085) / volume
    v_top, v_leg = 0.4 * 0.3 * 0.03, 0.03 * 0.03 * 0.2
    z_c = (v_top * 0.2 + 4 * v_leg * 0.085) / (v_top + 4 * v_leg)
    assert body.position[2] == pytest.approx(0.015 + z_c, abs=2e-3)
    assert np.linalg.norm(body.linear_velocity) < 1e-2


def _rotation(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def test_explicit_inertia_keeps_angular_momentum_with_products_of_inertia(client):
    inertia = np.array([[0.02, 0.001, -0.002], [0.001, 0.03, 0.0005], [-0.002, 0.0005, 0.025]])
    w0 = np.array([1.0, -2.0, 3.0])
    client.set_gravity((0, 0, 0))
    body = client.add_compound([{"shape": "sphere", "radius": 0.05}], mass=2.0, center_of_mass=(0.01, 0, 0),
                               inertia=inertia, angular_velocity=w0, position=(0, 0, 1))
    client.step(240)
    b = client.state().bodies[body]
    # the centre of mass sits 1 cm along x from the frame's origin and stays
    assert b.position == pytest.approx((0.01, 0, 1), abs=1e-12)
    # L = R I R^T w in the world is the L it started with
    R = _rotation(b.orientation)
    L = R @ inertia @ R.T @ np.asarray(b.angular_velocity)
    assert L == pytest.approx(inertia @ w0, rel=1e-9)
    assert np.linalg.norm(np.asarray(b.angular_velocity) - w0) > 0.1  # it did precess


@pytest.mark.parametrize("parts, extra, says", [
    ([], {}, "a compound takes 1 to 64 parts, got 0"),
    ([{"shape": "box", "half_extents": (0.1, 0.1, 0.1), "position": (0, 0, float("nan"))}], {},
     "parts[0].position must be finite"),
    ([{"shape": "sphere", "radius": -1}], {}, "parts[0].radius must be a finite number > 0"),
    ([{"shape": "sphere", "radius": 0.1}], {"mass": 1.0, "inertia": (1, 1, 3, 0, 0, 0)}, "triangle inequality"),
    ([{"shape": "sphere", "radius": 0.1}], {"mass": 1.0, "inertia": (1, -1, 1, 0, 0, 0)}, "positive definite"),
    ([{"shape": "sphere", "radius": 0.1}], {"inertia": (1, 1, 1, 0, 0, 0)}, "needs an explicit mass"),
])
def test_bad_compounds_are_refused_and_nothing_is_added(client, parts, extra, says):
    with pytest.raises(contactsim.CommandError) as err:
        client.add_compound(parts, position=(0, 0, 1), **extra)
    assert says in str(err.value)
    client.step(1)
    assert len(client.state().bodies) == 0


def test_barrier_refuses_a_compound_by_its_contract(client):
    client.set_contact_method("barrier")
    with pytest.raises(contactsim.CommandError) as err:
        client.add_compound(TABLE, position=(0, 0, 1))
    assert "contact method barrier does not simulate compound bodies" in str(err.value)
    client.set_contact_method("impulse")
    client.add_compound(TABLE, position=(0, 0, 1))
    with pytest.raises(contactsim.CommandError) as err:
        client.set_contact_method("barrier")
    assert "compound" in str(err.value)


def test_a_snapshot_keeps_compounds_exactly(client):
    client.add_plane((0, 0, 1), 0.0)
    client.add_compound(TABLE, position=(0, 0, 0.1), mass=3.0)
    client.add_compound([{"shape": "capsule", "radius": 0.03, "half_length": 0.1, "position": (0.05, 0, 0),
                          "orientation": (np.cos(0.4), np.sin(0.4), 0, 0)}],
                        position=(1, 0, 0.5), mass=1.0, center_of_mass=(0, 0.01, 0),
                        inertia=(0.004, 0.005, 0.003, 0.0002, 0, 0))
    client.step(60)
    client.snapshot("here")
    client.step(120)
    after = client.state().state_hash
    client.restore("here")
    client.step(120)
    assert client.state().state_hash == after
