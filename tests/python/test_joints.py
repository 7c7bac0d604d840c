"""Joints through the real server: a pendulum's period under impulse, lcp
(both solvers) and xpbd, a live switch to lcp with a joint present, bad
input, removal."""
import math

import numpy as np
import pytest

import contactsim
from contactsim import reply_t

G = 9.81
PIVOT = np.array([0.0, 0.0, 2.0])


def pendulum(client, length=1.0, theta0=0.05):
    """A sphere on a distance joint to the world at PIVOT, released at theta0."""
    client.reset()
    start = PIVOT + length * np.array([math.sin(theta0), 0.0, -math.cos(theta0)])
    bob = client.add_sphere(0.05, position=start)
    joint = client.add_joint("distance", bob, None, anchor=PIVOT)
    return bob, joint


METHODS = [("impulse", {}), ("lcp", {"solver": "pgs"}), ("lcp", {"solver": "lemke"}), ("xpbd", {})]


@pytest.mark.parametrize("method,params", METHODS, ids=["impulse", "lcp-pgs", "lcp-lemke", "xpbd"])
def test_pendulum_period_is_two_pi_root_l_over_g(client, method, params):
    """10 s of a 1 m pendulum at 0.05 rad, x sampled from every STATE (60 Hz):
    the zero crossings give the period 2 pi sqrt(l/g) to 0.5%."""
    bob, joint = pendulum(client)
    client.set_contact_method(method, **params)
    assert joint == 1
    samples = []
    client.on_state(lambda s: samples.append((s.time, s.bodies[bob].position[0])))
    client.step(2400)
    t, x = np.array(samples).T
    assert t[-1] == pytest.approx(10.0, rel=1e-9) and len(t) > 500
    down = np.nonzero(np.signbit(x[1:]) != np.signbit(x[:-1]))[0]
    crossings = t[down] + (t[down + 1] - t[down]) * x[down] / (x[down] - x[down + 1])
    period = 2.0 * (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    expected = 2.0 * math.pi * math.sqrt(1.0 / G)
    assert period == pytest.approx(expected, rel=0.005)
    # the rod keeps its length
    p = np.array(client.state().bodies[bob].position)
    assert np.linalg.norm(p - PIVOT) == pytest.approx(1.0, abs=1e-9)
    assert client.wait_for_status(timeout=3.0).method == method


def swing(client, method=None, params=None, steps=30):
    """A 1 m pendulum released at 0.3 rad swings 60 steps (0.25 s) under the
    server's default method (impulse); then, when `method` is given, the
    method is switched live; then `steps` single steps. Returns the bob's
    (position, velocity) after each of them."""
    bob, _ = pendulum(client, theta0=0.3)
    client.step(60)
    if method is not None:
        client.set_contact_method(method, **params)
    out = []
    for _ in range(steps):
        client.step(1)
        b = client.state().bodies[bob]
        out.append((np.array(b.position), np.array(b.linear_velocity)))
    return out


@pytest.mark.parametrize("solver", ["pgs", "lemke"])
def test_live_switch_to_lcp_with_a_joint_keeps_the_swing(client, solver):
    """A swinging pendulum switched live from impulse to lcp continues as if
    it had not been switched: lcp solves the same joint rows (exactly, for one
    row, by either solver) with the same post-stabilisation, so every step
    of the switched run stays within 1e-9 m and 1e-9 m/s of the unswitched
    one (a jump, a lost velocity or a re-solved pose would show), the rod
    keeps its length and the server reports the new method."""
    reference = swing(client)
    switched = swing(client, "lcp", {"solver": solver})
    for i, ((x_ref, v_ref), (x, v)) in enumerate(zip(reference, switched)):
        assert np.linalg.norm(x - x_ref) < 1e-9, "step %d: %.2e m off" % (i, np.linalg.norm(x - x_ref))
        assert np.linalg.norm(v - v_ref) < 1e-9, "step %d: %.2e m/s off" % (i, np.linalg.norm(v - v_ref))
        assert np.linalg.norm(x - PIVOT) == pytest.approx(1.0, abs=1e-9)
    assert np.linalg.norm(switched[-1][1]) > 0.5  # still swinging
    st = client.wait_for_status(timeout=3.0)
    assert st.method == "lcp" and ("solver=%s" % solver) in st.method_params.split()


def test_removing_the_joint_frees_the_body(client):
    bob, joint = pendulum(client, theta0=0.0)
    client.step(10)
    assert client.state().bodies[bob].linear_velocity[2] == pytest.approx(0.0, abs=1e-9)
    client.remove_joint(joint)
    r = client.step(1)
    assert client.state().bodies[bob].linear_velocity[2] == pytest.approx(-G * r.time / r.step, rel=1e-9)
    with pytest.raises(contactsim.CommandError) as e:
        client.remove_joint(joint)
    assert e.value.code == reply_t.NOT_FOUND and "unknown joint id 1" in e.value.message


def test_hinge_with_limits_and_a_world_weld(client):
    client.reset()
    door = client.add_box((0.4, 0.02, 0.8), position=(0.4, 0, 1))
    hinge = client.add_joint("hinge", door, None, anchor=(0, 0, 1), axis=(0, 0, 1), limits=(-0.5, 0.5))
    crate = client.add_box((0.1, 0.1, 0.1), position=(3, 0, 3))
    weld = client.add_joint("fixed", crate, None, anchor=(3, 0, 3))
    assert (hinge, weld) == (1, 2)
    client.set_velocity(door, (0, 0.8, 0), (0, 0, 2))  # swings about the hinge at 2 rad/s
    client.step(240)
    s = client.state()
    # the door turned to its stop (0.5 rad about +z, i.e. -0.5 rad of the world
    # relative to the door) and the crate has not moved
    w, x, y, z = s.bodies[door].orientation
    assert 2.0 * math.atan2(z, w) == pytest.approx(0.5, abs=1e-6)
    np.testing.assert_allclose(s.bodies[crate].position, (3, 0, 3), atol=1e-9)


def test_prismatic_slider_rests_on_its_limit_and_joint_friction_holds(client):
    """A carriage on a vertical slider falls 0.3 m onto its lower limit and
    rests there (a one-sided stop: no bounce, no sinking); a second one, its
    joint friction above its weight, does not move; a damped hinge swings
    down more slowly than an undamped one."""
    client.reset()
    carriage = client.add_box((0.1, 0.1, 0.1), position=(0, 0, 1))
    # the slide is the world's motion relative to the carriage along the
    # axis: with the axis down it is the carriage's height change
    client.add_joint("prismatic", carriage, None, anchor=(0, 0, 1), axis=(0, 0, -1), limits=(-0.3, 0.5))
    held = client.add_box((0.1, 0.1, 0.1), position=(2, 0, 1))
    client.add_joint("prismatic", held, None, anchor=(2, 0, 1), axis=(0, 0, 1), friction=1e4)
    free = client.add_sphere(0.05, position=(-2, 0, 1))
    damped = client.add_sphere(0.05, position=(-4, 0, 1))
    client.add_joint("hinge", free, None, anchor=(-1, 0, 1), axis=(0, 1, 0))
    client.add_joint("hinge", damped, None, anchor=(-3, 0, 1), axis=(0, 1, 0), damping=0.5)
    client.step(48)  # 0.2 s: both pendulums still falling from the horizontal
    s = client.state()
    assert s.bodies[damped].position[2] > s.bodies[free].position[2] + 1e-3
    client.step(192)
    s = client.state()
    np.testing.assert_allclose(s.bodies[carriage].position, (0, 0, 0.7), atol=1e-6)
    assert abs(s.bodies[carriage].linear_velocity[2]) < 1e-6
    np.testing.assert_allclose(s.bodies[held].position, (2, 0, 1), atol=1e-9)


BAD = [
    ("unknown_body_a", lambda c, b: c.add_joint("ball", 999, None, anchor=(0, 0, 1)),
     ["body_a", "999"], reply_t.NOT_FOUND),
    ("unknown_body_b", lambda c, b: c.add_joint("ball", b, 999, anchor=(0, 0, 1)),
     ["body_b", "999"], reply_t.NOT_FOUND),
    ("self_joint", lambda c, b: c.add_joint("ball", b, b, anchor=(0, 0, 1)),
     ["itself", str(1)], reply_t.INVALID_ARGUMENT),
    ("zero_length", lambda c, b: c.add_joint("distance", b, None, anchor=(0, 0, 2), length=0.0),
     ["length", "0"], reply_t.INVALID_ARGUMENT),
    ("negative_length", lambda c, b: c.add_joint("distance", b, None, anchor=(0, 0, 2), length=-1.0),
     ["length", "-1"], reply_t.INVALID_ARGUMENT),
    ("nan_anchor", lambda c, b: c.add_joint("ball", b, None, anchor=(math.nan, 0, 1)),
     ["anchor"], reply_t.INVALID_ARGUMENT),
    ("zero_axis", lambda c, b: c.add_joint("hinge", b, None, anchor=(0, 0, 1), axis=(0, 0, 0)),
     ["axis"], reply_t.INVALID_ARGUMENT),
    ("swapped_limits", lambda c, b: c.add_joint("hinge", b, None, anchor=(0, 0, 1), axis=(0, 1, 0),
                                                limits=(0.5, -0.5)),
     ["lower", "upper"], reply_t.INVALID_ARGUMENT),
    ("prismatic_zero_axis", lambda c, b: c.add_joint("prismatic", b, None, anchor=(0, 0, 1), axis=(0, 0, 0)),
     ["axis"], reply_t.INVALID_ARGUMENT),
    ("prismatic_swapped_limits", lambda c, b: c.add_joint("prismatic", b, None, anchor=(0, 0, 1), axis=(1, 0, 0),
                                                          limits=(2.0, 1.0)),
     ["lower", "upper"], reply_t.INVALID_ARGUMENT),
    ("negative_damping", lambda c, b: c.add_joint("hinge", b, None, anchor=(0, 0, 2), axis=(0, 1, 0), damping=-1.0),
     ["damping", "-1"], reply_t.INVALID_ARGUMENT),
    ("ball_friction", lambda c, b: c.add_joint("ball", b, None, anchor=(0, 0, 2), friction=0.5),
     ["friction", "ball"], reply_t.INVALID_ARGUMENT),
    ("remove_unknown", lambda c, b: c.remove_joint(999), ["999"], reply_t.NOT_FOUND),
]


def run(client, bad=None):
    """Final state and the next joint id of: a pendulum, step, [bad], step, a
    probe joint, step."""
    bob, _ = pendulum(client, theta0=0.3)
    client.step(3)
    if bad is not None:
        bad(client, bob)
    client.step(3)
    probe_body = client.add_sphere(0.05, position=(2, 0, 1))
    probe = client.add_joint("ball", probe_body, None, anchor=(2, 0, 1.5))
    client.step(3)
    return client.state(), probe


@pytest.mark.parametrize("name,bad,words,code", BAD, ids=[b[0] for b in BAD])
def test_bad_joint_input_is_rejected_and_changes_nothing(client, name, bad, words, code):
    reference, ref_probe = run(client)
    errors = []

    def checked(c, bob):
        with pytest.raises(contactsim.CommandError) as e:
            bad(c, bob)
        errors.append(e.value)

    after, probe = run(client, checked)
    err = errors[0]
    for w in words:
        assert w in err.message, "message %r does not name %r" % (err.message, w)
    assert err.code == code, "code %s, want %s (%s)" % (err.code_name, code, err.message)
    assert after.state_hash == reference.state_hash
    assert after == reference, "world changed by a rejected joint command"
    assert probe == ref_probe, "a rejected command used up a joint id"


def test_unknown_kind_is_refused_by_the_client(client):
    with pytest.raises(ValueError, match="kind must be one of"):
        client.add_joint("slider", 1, None, anchor=(0, 0, 0))
