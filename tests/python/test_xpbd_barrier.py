"""The xpbd and barrier contact methods switched live through the real server
with the Python client. The switch scenarios are test_switch.py's, run here
for switches between impulse and each of these methods: mid-fall and
mid-rest keep every body's state and add no energy, and the friction
stopping distance holds. CONTACTS carries the weight as a force.

A box that impulse rests touching is a placed pair for the barrier method
after the switch (docs/methods/barrier.md, "Bodies placed touching"): it
settles within 2e-2 d_hat instead of being lifted to the barrier's gap."""
import numpy as np
import pytest

import test_switch as base
from test_switch import BOX_MASS, G, HALF, use

METHODS = ["xpbd", "barrier"]
PAIRS = [(a, b) for m in METHODS for (a, b) in (("impulse", m), (m, "impulse"))]
D_HAT = 1e-3   # m, the barrier method's default activation distance


@pytest.mark.parametrize("first,second", PAIRS)
def test_switch_mid_fall_keeps_the_trajectory(client, first, second):
    base.test_switch_mid_fall_keeps_the_trajectory(client, first, second)


@pytest.mark.parametrize("first,second", PAIRS)
def test_switch_mid_rest_keeps_the_box_still(client, first, second):
    base.test_switch_mid_rest_keeps_the_box_still(client, first, second)


def test_switch_from_impulse_to_barrier_at_rest_keeps_the_box_in_place(client):
    use(client, "impulse")
    client.add_plane((0, 0, 1), 0.0, restitution=0.0)
    box = client.add_box((HALF,) * 3, position=(0, 0, HALF), restitution=0.0)
    client.step(240)
    before = client.state().bodies[box]
    use(client, "barrier")
    worst_move = 0.0
    for _ in range(48):                    # 1 s under the barrier
        client.step(5)
        b = client.state().bodies[box]
        worst_move = max(worst_move, np.linalg.norm(b.position - before.position))
    b = client.state().bodies[box]
    # a placed pair gives way by at most its width, 2e-2 D_HAT, and pushes nothing
    assert worst_move < 2e-2 * D_HAT
    assert np.linalg.norm(b.linear_velocity) < 1e-3
    assert np.linalg.norm(b.orientation - before.orientation) < 1e-6


def test_sliding_box_stops_at_the_coulomb_distance_xpbd(client):
    base.test_sliding_box_stops_at_the_coulomb_distance(client, "xpbd")


def test_sliding_box_stops_at_the_coulomb_distance_barrier(client):
    # The box starts D_HAT / 2 above the plane, at a resting gap: placed
    # touching it would rest on placed pairs, 50 times stiffer, whose
    # rocking costs the slide 1.7% (docs/methods/barrier.md, "Bodies placed
    # touching"), which is not friction's doing.
    mu, v0 = 0.4, 3.0
    use(client, "barrier")
    client.add_plane((0, 0, 1), 0.0, restitution=0.0, friction=mu)
    box = client.add_box((HALF,) * 3, position=(0, 0, HALF + D_HAT / 2), restitution=0.0, friction=mu)
    client.set_velocity(box, (v0, 0, 0), (0, 0, 0))
    client.step(480)
    b = client.state().bodies[box]
    expected = v0 * v0 / (2 * mu * G)
    assert b.position[0] == pytest.approx(expected, rel=0.03)
    assert np.linalg.norm(b.linear_velocity) < 1e-3


@pytest.mark.parametrize("name", METHODS)
def test_contacts_are_forces_that_carry_the_weight(client, name):
    use(client, name)
    plane = client.add_plane((0, 0, 1), 0.0, restitution=0.0)
    box = client.add_box((HALF,) * 3, position=(0, 0, HALF), restitution=0.0)
    client.step(241)
    cs = client.contacts()
    assert cs.method == name and cs.value_kind == "force"
    mine = [c for c in cs if {c.body_a, c.body_b} == {plane, box}]
    assert mine
    assert sum(c.normal_value for c in mine) == pytest.approx(BOX_MASS * G, rel=0.05)
