"""The xpbd and barrier contact methods switched live through the real server
with the Python client. The switch scenarios are test_switch.py's, run here
for switches between impulse and each of these methods: mid-fall and
mid-rest keep every body's state and add no energy, and the friction
stopping distance holds. CONTACTS carries the weight as a force."""
import pytest

import test_switch as base
from test_switch import BOX_MASS, G, HALF, use

METHODS = ["xpbd"]
PAIRS = [(a, b) for m in METHODS for (a, b) in (("impulse", m), (m, "impulse"))]


@pytest.mark.parametrize("first,second", PAIRS)
def test_switch_mid_fall_keeps_the_trajectory(client, first, second):
    base.test_switch_mid_fall_keeps_the_trajectory(client, first, second)


@pytest.mark.parametrize("first,second", PAIRS)
def test_switch_mid_rest_keeps_the_box_still(client, first, second):
    base.test_switch_mid_rest_keeps_the_box_still(client, first, second)


@pytest.mark.parametrize("name", METHODS)
def test_sliding_box_stops_at_the_coulomb_distance(client, name):
    base.test_sliding_box_stops_at_the_coulomb_distance(client, name)


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
