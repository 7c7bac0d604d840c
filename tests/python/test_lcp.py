"""The lcp contact method through the real server: a live switch
impulse -> lcp -> penalty -> lcp (lemke) keeps positions and adds no energy,
a sphere bounces to e^2 h under lcp, and bad lcp parameters are refused by
name."""
import numpy as np
import pytest

import contactsim
from test_bounce import first_apex  # RADIUS there is 0.1 m too

G = 9.81
DT = 1.0 / 240
RADIUS = 0.1
HALF = 0.1
MASS = 8.0
# a switch step moves a body by v h + O(g h^2) (1.7e-4 m) or by the new
# method's rest depth (penalty: m g / kp = 0.08 mm); 1 mm bounds both
MAX_JUMP = 1e-3   # m
# impulse may lift a box sunk deeper than its slop (m g d < 0.08 J for the
# 8 kg box); lcp and penalty add none
MAX_ENERGY_RISE = 0.1  # J


def energy(state, ids, inertia):
    """Kinetic plus potential energy (J) of bodies with isotropic inertia
    (sphere, cube), each of mass MASS."""
    e = 0.0
    for i in ids:
        b = state.bodies[i]
        v, w = np.asarray(b.linear_velocity), np.asarray(b.angular_velocity)
        e += 0.5 * MASS * v.dot(v) + 0.5 * inertia[i] * w.dot(w) + MASS * G * b.position[2]
    return e


def test_live_switch_keeps_positions_and_energy(client):
    client.add_plane((0, 0, 1), 0.0, restitution=0.5)
    ball = client.add_sphere(RADIUS, position=(0, 0, 3.1), mass=MASS, restitution=0.5)
    box = client.add_box((HALF, HALF, HALF), position=(1, 0, HALF), mass=MASS, restitution=0.5)
    inertia = {ball: 0.4 * MASS * RADIUS ** 2, box: MASS * 2 * HALF ** 2 / 3}
    ids = (ball, box)
    client.step(48)  # 0.2 s under impulse: the ball falls, the box rests
    for name, params in (("lcp", {"solver": "pgs"}), ("penalty", {}), ("lcp", {"solver": "lemke"})):
        client.set_contact_method(name, **params)
        e0 = energy(client.state(), ids, inertia)
        for _ in range(24):
            before = client.state()
            client.step(1)
            after = client.state()
            for i in ids:
                x0, x1 = np.asarray(before.bodies[i].position), np.asarray(after.bodies[i].position)
                v0 = np.asarray(before.bodies[i].linear_velocity)
                jump = np.linalg.norm(x1 - x0 - v0 * DT)
                assert jump < MAX_JUMP, "%s: body %d jumped %.2e m" % (name, i, jump)
            rise = energy(after, ids, inertia) - e0
            assert rise < MAX_ENERGY_RISE, "%s: energy rose by %.3f J" % (name, rise)
        st = client.wait_for_status(timeout=3.0)
        assert st.method == name
    assert client.state().bodies[box].position[2] == pytest.approx(HALF, abs=1e-3)
    assert client.state().bodies[ball].position[2] > 0.5  # still falling


@pytest.mark.parametrize("solver", ["pgs", "lemke"])
def test_bounce_under_lcp_reaches_e_squared_times_drop(client, solver):
    client.set_contact_method("lcp", solver=solver)
    client.add_plane((0, 0, 1), 0.0, restitution=0.5)
    ball = client.add_sphere(RADIUS, position=(0, 0, 1.0 + RADIUS), restitution=0.5)
    apex = first_apex(client, ball, int(1.5 / DT))
    assert apex == pytest.approx(0.25, rel=0.02), "apex %.5f m" % apex
    cs = client.contacts()
    assert cs is None or cs.method == "lcp"


def test_bad_lcp_parameters_are_refused_by_name(client):
    with pytest.raises(contactsim.CommandError) as e:
        client.set_contact_method("lcp", solver="dantzig")
    assert "solver" in str(e.value) and "dantzig" in str(e.value)
    client.set_contact_method("lcp", solver="lemke", iterations=50)
    st = client.wait_for_status(timeout=3.0)
    assert st.method == "lcp" and "solver=lemke" in st.method_params.split()
