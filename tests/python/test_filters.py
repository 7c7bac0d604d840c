"""Collision filtering through the real server (docs/physics.md, "Collision
filtering"): a filter given at ADD, a SET_FILTER that drops the top of a
sleeping stack through the box below it, kept across a snapshot and
restore, and bad input refused with a message and nothing changed."""
import pytest

import contactsim
from contactsim import reply_t

HALF = 0.1  # m, the boxes


def stack(client, **lower_filter):
    """Ground, a lower box (category 2 unless told) and an upper box resting on it."""
    client.add_plane((0, 0, 1), 0.0)
    lower_filter.setdefault("collision_category", 2)
    lower = client.add_box((HALF, HALF, HALF), position=(0, 0, HALF + 1e-3), restitution=0.0, **lower_filter)
    upper = client.add_box((HALF, HALF, HALF), position=(0, 0, 3 * HALF + 2e-3), restitution=0.0)
    return lower, upper


def test_set_filter_drops_the_top_of_a_sleeping_stack_through_the_box_below(client):
    lower, upper = stack(client)
    client.step(480)
    assert client.state().bodies[upper].position[2] == pytest.approx(3 * HALF, abs=0.01)
    client.wait_for_status(lambda s: s.num_sleeping == 2, timeout=5.0)
    # the upper box now touches category 1 (the ground) only
    r = client.set_filter(upper, collision_category=1, collision_mask=1)
    assert r.code == reply_t.OK and "collision filter" in r.message
    client.step(240)
    s = client.state()
    assert s.bodies[upper].position[2] == pytest.approx(HALF, abs=0.01)
    assert s.bodies[lower].position[2] == pytest.approx(HALF, abs=0.01)


def test_masks_given_at_add_let_the_boxes_pass_through_each_other(client):
    client.add_plane((0, 0, 1), 0.0)
    a = client.add_box((HALF, HALF, HALF), position=(0, 0, HALF + 0.02), restitution=0.0,
                       collision_category=2, collision_mask=1)
    b = client.add_box((HALF, HALF, HALF), position=(0, 0, 3 * HALF + 0.1), restitution=0.0,
                       collision_category=4, collision_mask=0xFFFFFFFF)
    client.step(360)
    s = client.state()
    assert s.bodies[a].position[2] == pytest.approx(HALF, abs=0.01)
    assert s.bodies[b].position[2] == pytest.approx(HALF, abs=0.01)


def test_a_negative_group_falls_through_itself(client):
    client.add_plane((0, 0, 1), 0.0)
    model = [client.add_box((HALF, HALF, HALF), position=(0, 0, HALF + 0.01 + 0.25 * i), restitution=0.0,
                            collision_group=-1) for i in range(3)]
    other = client.add_box((HALF, HALF, HALF), position=(0, 0, 1.0), restitution=0.0, collision_group=-2)
    client.step(480)
    s = client.state()
    for body in model:
        assert s.bodies[body].position[2] == pytest.approx(HALF, abs=0.01)
    assert s.bodies[other].position[2] == pytest.approx(3 * HALF, abs=0.01)


def test_a_snapshot_keeps_the_filter(client):
    lower, upper = stack(client)
    client.step(120)
    client.set_filter(upper, collision_category=1, collision_mask=1)
    client.snapshot("filtered")
    client.set_filter(upper)  # back to the default: the stack stands again
    client.restore("filtered")
    client.step(240)
    assert client.state().bodies[upper].position[2] == pytest.approx(HALF, abs=0.01)


def test_collide_connected_is_sent_and_checked(client):
    a = client.add_sphere(0.1, position=(0, 0, 1))
    b = client.add_sphere(0.1, position=(0, 0, 1.15))
    assert client.add_joint("ball", a, b, anchor=(0, 0, 1.1), collide_connected=True) >= 1
    with pytest.raises(TypeError, match="collide_connected"):
        client.add_joint("ball", a, b, anchor=(0, 0, 1.1), collide_connected=1)


@pytest.mark.parametrize("kwargs,error,words", [
    (dict(collision_category=-1), ValueError, "collision_category must be in [0, 4294967295], got -1"),
    (dict(collision_mask=1 << 32), ValueError, "collision_mask must be in [0, 4294967295], got 4294967296"),
    (dict(collision_group=1 << 31), ValueError, "collision_group must be in [-2147483648, 2147483647]"),
    (dict(collision_category=1.0), TypeError, "collision_category must be an integer, got 1.0"),
    (dict(collision_mask="all"), TypeError, "collision_mask must be an integer, got 'all'"),
    (dict(collision_group=True), TypeError, "collision_group must be an integer, got True"),
])
def test_bad_filter_values_are_refused_before_sending(client, kwargs, error, words):
    box = client.add_box((HALF, HALF, HALF), position=(0, 0, 1))
    with pytest.raises(error) as e:
        client.set_filter(box, **kwargs)
    assert words in str(e.value)
    with pytest.raises(error):
        client.add_sphere(0.1, position=(1, 0, 1), **kwargs)
    client.step(1)
    assert sorted(client.state().bodies) == [box]


def test_set_filter_on_an_unknown_body_or_the_world_is_not_found_and_changes_nothing(client):
    lower, upper = stack(client)
    client.step(10)
    before = client.state().state_hash
    for body, words in ((999999, "unknown body id 999999"), (0, "body id 0 is the world")):
        with pytest.raises(contactsim.CommandError) as e:
            client.set_filter(body, collision_category=2, collision_mask=1)
        assert e.value.code == reply_t.NOT_FOUND
        assert words in str(e.value)
    assert client.state().state_hash == before
    client.step(240)  # the stack still stands: no filter changed
    assert client.state().bodies[upper].position[2] == pytest.approx(3 * HALF, abs=0.01)
