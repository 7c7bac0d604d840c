"""Every bad input gets an error reply naming the field, and leaves the world
exactly as it was.

The server publishes STATE only when it steps, so "as it was" is checked by
determinism: load a scene, step, send the bad command, step, add a probe
body, step; the final STATE (hash, clock and every body, bit for bit) and
the probe's id must equal those of the same run without the bad command.
"""
import math
import random
import time

import lcm
import pytest

import contactsim
from contactsim import reply_t

SCENE = """
gravity { z: -9.81 }
bodies { name: "ground" plane { normal { z: 1 } offset: 0 } }
bodies { name: "ball" sphere { radius: 0.1 } position { z: 0.5 }
         linear_velocity { x: 0.3 y: -0.2 } angular_velocity { z: 1.5 } mass: 2 }
bodies { name: "crate" box { half_extents { x: 0.1 y: 0.2 z: 0.05 } } position { x: 1 z: 0.3 }
         orientation { w: 0.9 x: 0.1 y: 0.3 } angular_velocity { x: 2 y: -1 } density: 500 }
"""

NAN, INF = math.nan, math.inf
MISSING = 999  # no body has this id

# (id, command, words the error message must contain, expected code or None for any error)
BAD = [
    ("nan_position", lambda c: c.add_sphere(0.1, position=(NAN, 0, 1)), ["position"], reply_t.INVALID_ARGUMENT),
    ("inf_position", lambda c: c.add_sphere(0.1, position=(0, INF, 1)), ["position"], reply_t.INVALID_ARGUMENT),
    ("negative_radius", lambda c: c.add_sphere(-1.0), ["radius"], reply_t.INVALID_ARGUMENT),
    ("zero_radius", lambda c: c.add_sphere(0.0), ["radius"], reply_t.INVALID_ARGUMENT),
    ("negative_mass", lambda c: c.add_sphere(0.1, mass=-1.0), ["mass"], reply_t.INVALID_ARGUMENT),
    ("mass_and_density", lambda c: c.add_sphere(0.1, mass=1.0, density=1000.0), ["mass", "density"],
     reply_t.INVALID_ARGUMENT),
    ("restitution_above_1", lambda c: c.add_sphere(0.1, restitution=1.5), ["restitution"], reply_t.INVALID_ARGUMENT),
    ("negative_box", lambda c: c.add_box((0.1, -0.1, 0.1)), ["half_extents"], reply_t.INVALID_ARGUMENT),
    ("zero_quaternion_pose", lambda c: c.set_pose(1, (0, 0, 1), (1e-12, 0, 0, 0)), ["orientation"],
     reply_t.INVALID_ARGUMENT),
    ("nan_velocity", lambda c: c.set_velocity(2, (NAN, 0, 0), (0, 0, 0)), ["velocity"], reply_t.INVALID_ARGUMENT),
    ("remove_unknown", lambda c: c.remove_body(MISSING), [str(MISSING)], reply_t.NOT_FOUND),
    ("set_pose_unknown", lambda c: c.set_pose(MISSING, (0, 0, 1), (1, 0, 0, 0)), [str(MISSING)], reply_t.NOT_FOUND),
    ("apply_force_unknown", lambda c: c.apply_force(MISSING, (0, 0, 1)), [str(MISSING)], reply_t.NOT_FOUND),
    ("apply_impulse_unknown", lambda c: c.apply_impulse(MISSING, (0, 0, 1)), [str(MISSING)], reply_t.NOT_FOUND),
    ("unknown_method", lambda c: c.set_contact_method("nosuch"), ["nosuch"], None),
    ("unknown_parameter", lambda c: c.set_contact_method("impulse", nosuch_param="1"), ["nosuch_param"], None),
    ("out_of_range_parameter", lambda c: c.set_contact_method("impulse", iterations="-3"), ["iterations", "-3"],
     reply_t.INVALID_ARGUMENT),
    ("zero_timestep", lambda c: c.set_timestep(0.0), ["dt"], reply_t.INVALID_ARGUMENT),
    ("nan_gravity", lambda c: c.set_gravity((0, 0, NAN)), ["gravity"], reply_t.INVALID_ARGUMENT),
    ("zero_steps", lambda c: c.step(0), ["steps"], reply_t.INVALID_ARGUMENT),
    ("negative_real_time_factor", lambda c: c.set_mode("realtime", real_time_factor=-1.0), ["real_time_factor"],
     reply_t.INVALID_ARGUMENT),
    ("fixed_and_kinematic", lambda c: c.add_box((0.1, 0.1, 0.1), fixed=True, kinematic=True), ["fixed", "kinematic"],
     reply_t.INVALID_ARGUMENT),
    ("force_on_static", lambda c: c.apply_force(1, (0, 0, 1)), ["static"], reply_t.FAILED_PRECONDITION),
    ("missing_scene_file", lambda c: c.load_scene("/nonexistent/scene.pbtxt"), ["/nonexistent/scene.pbtxt"], None),
]


@pytest.fixture
def scene(tmp_path):
    path = tmp_path / "validation-scene.pbtxt"
    path.write_text(SCENE)
    return path


def run(client, scene, bad=None):
    """The final state and the probe id of load, step, [bad], step, add probe, step."""
    client.reset()
    client.load_scene(str(scene))
    client.step(1)
    before = client.state()
    assert len(before.bodies) == 3
    if bad is not None:
        bad(client)
    client.step(1)
    probe = client.add_sphere(0.05, position=(3, 0, 1))
    client.step(1)
    return client.state(), probe


@pytest.mark.parametrize("name,bad,words,code", BAD, ids=[b[0] for b in BAD])
def test_bad_input_is_rejected_and_changes_nothing(client, scene, name, bad, words, code):
    reference, ref_probe = run(client, scene)
    errors = []

    def checked(c):
        with pytest.raises(contactsim.CommandError) as e:
            bad(c)
        errors.append(e.value)

    after, probe = run(client, scene, checked)
    err = errors[0]
    assert not isinstance(err, contactsim.TimeoutError), "no reply: %s" % err
    for w in words:
        assert w in err.message, "message %r does not name %r" % (err.message, w)
    if code is not None:
        assert err.code == code, "code %s, want %s (%s)" % (err.code_name, code, err.message)
    else:
        assert err.code != reply_t.OK
    assert after.state_hash == reference.state_hash
    assert after == reference, "world changed by a rejected command"
    assert probe == ref_probe, "a rejected command used up a body id"


def test_status_counts_rejections_and_shows_the_last_error(client):
    with pytest.raises(contactsim.CommandError) as e:
        client.add_sphere(-1.0)
    st = client.wait_for_status(lambda s: s.commands_rejected >= 1, timeout=3.0)
    assert st.commands_rejected == 1 and st.last_error == e.value.message


@pytest.mark.parametrize("channel", ["BODY_CMD", "SCENE_CMD"])
def test_undecodable_payload_gets_decode_error(server, scene, channel):
    client = server.client
    reference, ref_probe = run(client, scene)
    replies = []
    client.on_reply(lambda r: replies.append(r) if r.client_id == "" else None)
    client.reset()
    client.load_scene(str(scene))
    client.step(1)
    rng = random.Random(7)
    junk = [bytes(rng.randrange(256) for _ in range(n)) for n in (0, 1, 7, 64, 1000)]
    m = contactsim.body_cmd_t() if channel == "BODY_CMD" else contactsim.scene_cmd_t()
    junk.append(m.encode()[:20])  # a valid fingerprint, then too few bytes
    pub = lcm.LCM(server.url)
    for payload in junk:
        pub.publish(client.channels[channel], payload)
    deadline = time.monotonic() + 5.0
    while len(replies) < len(junk) and time.monotonic() < deadline:
        time.sleep(0.01)
    time.sleep(0.1)  # and no extra replies
    assert len(replies) == len(junk)
    for r in replies:
        assert (r.code, r.client_id, r.request_id) == (reply_t.DECODE_ERROR, "", -1), r.message
        assert r.message
    client.step(1)
    probe = client.add_sphere(0.05, position=(3, 0, 1))
    client.step(1)
    assert client.state() == reference and probe == ref_probe
