"""Contact methods switched live through the real server with the Python client:
mid-fall and mid-rest, in both directions, keep every body's state (no jump)
and add no energy beyond the new method's own transient; CONTACTS says which
method produced it and whether its values are impulses or forces; the
friction stopping distance holds through the server."""
import numpy as np
import pytest

G = 9.81
HALF = 0.1                      # m, cube half size
BOX_MASS = 1000.0 * (2 * HALF) ** 3   # kg, default density 1000 kg/m^3
BOX_INERTIA = BOX_MASS * (2 * HALF) ** 2 / 6.0  # kg m^2, a cube about any axis

PAIRS = [("impulse", "penalty"), ("penalty", "impulse")]


def box_energy(body):
    """Kinetic plus potential energy of the test cube (J)."""
    v, w = body.linear_velocity, body.angular_velocity
    return 0.5 * BOX_MASS * v.dot(v) + 0.5 * BOX_INERTIA * w.dot(w) + BOX_MASS * G * body.position[2]


def use(client, name):
    reply = client.set_contact_method(name)
    assert name in reply.message, reply.message  # the reply says what is active
    return reply


@pytest.mark.parametrize("first,second", PAIRS)
def test_switch_mid_fall_keeps_the_trajectory(client, first, second):
    use(client, first)
    client.add_plane((0, 0, 1), 0.0, restitution=0.0)
    box = client.add_box((HALF,) * 3, position=(0, 0, 2.0), restitution=0.0)
    r = client.step(48)                    # 0.2 s into a 0.6 s fall
    dt = r.time / 48
    before = client.state().bodies[box]
    e0 = box_energy(before)
    use(client, second)
    assert client.wait_for_status(lambda s: s.method == second, timeout=3.0).method == second
    client.step(1)
    after = client.state().bodies[box]
    # free flight under either method: x advances by v dt - g dt^2 / 2 up to
    # the integrators' O(g dt^2) difference (8.5e-5 m at dt = 1/240 s)
    predicted = before.position[2] + before.linear_velocity[2] * dt - 0.5 * G * dt * dt
    assert after.position[2] == pytest.approx(predicted, abs=G * dt * dt)
    assert abs(after.position[0]) < 1e-12 and abs(after.position[1]) < 1e-12
    assert box_energy(after) == pytest.approx(e0, abs=1e-3 * e0)
    # landing under the new method: it comes to rest on the plane (e = 0),
    # and the energy never rises above the energy at the switch
    worst = -np.inf
    for _ in range(40):
        client.step(6)
        worst = max(worst, box_energy(client.state().bodies[box]))
    rest = client.state().bodies[box]
    assert worst <= e0 + 1e-6 * e0
    assert rest.position[2] == pytest.approx(HALF, abs=2e-3)
    assert np.linalg.norm(rest.linear_velocity) < 1e-2


@pytest.mark.parametrize("first,second", PAIRS)
def test_switch_mid_rest_keeps_the_box_still(client, first, second):
    use(client, first)
    client.add_plane((0, 0, 1), 0.0, restitution=0.0)
    box = client.add_box((HALF,) * 3, position=(0, 0, HALF), restitution=0.0)
    client.step(240)                       # settle for 1 s under the first method
    before = client.state().bodies[box]
    e0 = box_energy(before)
    use(client, second)
    worst_e, worst_move = -np.inf, 0.0
    for _ in range(48):                    # 1 s under the new method
        client.step(5)
        b = client.state().bodies[box]
        worst_e = max(worst_e, box_energy(b))
        worst_move = max(worst_move, np.linalg.norm(b.position - before.position))
    # the two methods rest at different depths (impulse: within its 1 mm
    # slop; penalty: m g / kp = 8e-5 m), so the box may move by about that
    # much, and no more; the transient adds at most a micro-joule
    assert worst_move < 1.5e-3
    assert worst_e < e0 + 1e-4
    b = client.state().bodies[box]
    assert np.linalg.norm(b.linear_velocity) < 1e-3
    assert np.linalg.norm(b.orientation - before.orientation) < 1e-6


@pytest.mark.parametrize("name,kind,scale", [("impulse", "impulse", "dt"), ("penalty", "force", "1")])
def test_contacts_are_labelled_and_carry_the_weight(client, name, kind, scale):
    use(client, name)
    plane = client.add_plane((0, 0, 1), 0.0, restitution=0.0)
    box = client.add_box((HALF,) * 3, position=(0, 0, HALF), restitution=0.0)
    r = client.step(240)
    dt = r.time / 240
    client.step(1)
    cs = client.contacts()
    assert cs.method == name and cs.value_kind == kind
    mine = [c for c in cs if {c.body_a, c.body_b} == {plane, box}]
    assert len(mine) == 4, mine            # one per corner of the bottom face
    total = sum(c.normal_value for c in mine)
    weight = BOX_MASS * G * (dt if scale == "dt" else 1.0)
    assert total == pytest.approx(weight, rel=0.05)


@pytest.mark.parametrize("name", ["impulse", "penalty"])
def test_sliding_box_stops_at_the_coulomb_distance(client, name):
    mu, v0 = 0.4, 3.0
    use(client, name)
    client.add_plane((0, 0, 1), 0.0, restitution=0.0, friction=mu)
    box = client.add_box((HALF,) * 3, position=(0, 0, HALF), restitution=0.0, friction=mu)
    client.set_velocity(box, (v0, 0, 0), (0, 0, 0))
    client.step(480)                       # stops after v0 / (mu g) = 0.76 s
    b = client.state().bodies[box]
    expected = v0 * v0 / (2 * mu * G)
    assert b.position[0] == pytest.approx(expected, rel=0.03)
    assert np.linalg.norm(b.linear_velocity) < 1e-3


def test_status_carries_the_contract_of_the_active_method(client):
    # Verifies that STATUS says what the active method simulates
    # (docs/physics.md, "Method contract") and follows a switch.
    use(client, "impulse")
    st = client.wait_for_status(lambda s: s.method == "impulse", timeout=3.0)
    assert st.contract() == {"joints": True, "restitution": True, "kinematic": True, "contact_forces": True,
                             "friction": "coulomb disk"}
    use(client, "barrier")
    c = client.wait_for_status(lambda s: s.method == "barrier", timeout=3.0).contract()
    assert (c["joints"], c["restitution"], c["kinematic"]) == (False, False, False)
    assert c["friction"].startswith("regularized")


def test_barrier_refuses_restitution_and_says_why(client):
    # Verifies the refusals of the barrier method's contract through the real
    # server: a switch while a body bounces, a bouncy body added under it and
    # a restitution set under it are each refused with FAILED_PRECONDITION
    # naming the body and the value, and leave the method and the body as
    # they were.
    import contactsim
    use(client, "impulse")
    plane = client.add_plane((0, 0, 1), 0.0, restitution=0.0)
    ball = client.add_sphere(0.1, position=(0, 0, 1), restitution=0.5)
    with pytest.raises(contactsim.CommandError) as e:
        client.set_contact_method("barrier")
    assert e.value.code_name == "FAILED_PRECONDITION"
    assert "barrier does not simulate restitution: body %d has restitution 0.5" % ball in e.value.message
    assert client.wait_for_status(lambda s: s.step >= 0, timeout=3.0).method == "impulse"
    client.set_material(ball, restitution=0.0)
    use(client, "barrier")
    with pytest.raises(contactsim.CommandError) as e:
        client.add_sphere(0.1, position=(1, 0, 1), restitution=0.3)
    assert e.value.code_name == "FAILED_PRECONDITION" and "restitution 0.3" in e.value.message
    with pytest.raises(contactsim.CommandError) as e:
        client.set_material(plane, restitution=0.2)
    assert e.value.code_name == "FAILED_PRECONDITION" and "body %d has restitution 0.2" % plane in e.value.message
    assert sorted(client.state().bodies) == [plane, ball]
