"""A sphere (e = 0.5) dropped from 1 m onto a plane (e = 0.5) rebounds to 0.25 m;
a pair uses restitution max(e_ball, e_plane)."""
import pytest

RADIUS = 0.1
DROP = 1.0


def first_apex(client, ball, max_steps):
    """Steps one step at a time; the highest lowest-point after the first bounce."""
    bounced, apex = False, None
    for _ in range(max_steps):
        client.step(1)
        b = client.state().bodies[ball]
        z, vz = b.position[2] - RADIUS, b.linear_velocity[2]
        if not bounced:
            bounced = vz > 0
            continue
        apex = z if apex is None else max(apex, z)
        if vz < 0:
            return apex
    pytest.fail("no apex after the first bounce within %d steps (bounced: %s)" % (max_steps, bounced))


@pytest.mark.parametrize("dt", [None, 1.0 / 1000])
def test_bounce_apex_is_e_squared_times_drop(client, dt):
    if dt is not None:
        client.set_timestep(dt)
    client.add_plane((0, 0, 1), 0.0, restitution=0.5)
    ball = client.add_sphere(RADIUS, position=(0, 0, DROP + RADIUS), restitution=0.5)
    r = client.step(1)
    max_steps = int(1.5 / r.time)  # fall 0.45 s + rise 0.23 s, with margin
    apex = first_apex(client, ball, max_steps)
    assert apex == pytest.approx(0.25 * DROP, rel=0.02), "apex %.5f m (dt %g s)" % (apex, r.time)


@pytest.mark.parametrize("e_ball,e_plane", [(0.9, 0.1), (0.0, 0.5), (0.3, 0.7)])
def test_pair_restitution_is_the_max(client, e_ball, e_plane):
    client.add_plane((0, 0, 1), 0.0, restitution=e_plane)
    ball = client.add_sphere(RADIUS, position=(0, 0, DROP + RADIUS), restitution=e_ball)
    r = client.step(1)
    apex = first_apex(client, ball, int(2.5 / r.time))
    e = max(e_ball, e_plane)
    assert apex == pytest.approx(e * e * DROP, rel=0.02), "apex %.5f m, e = %g" % (apex, e)
