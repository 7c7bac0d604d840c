"""Ray casts, range sensors and contact sensors through a real server over
LCM: answers against hand-computed geometry, garbage refused with the
server's message, readings that repeat bit for bit after a rewind and a
recorded run that ``--replay`` re-simulates identically."""
import math
import subprocess

import numpy as np
import pytest

import contactsim

from conftest import CONFIG, SERVER_BIN
from lcm_recorder import LcmRecorder

G = 9.81


def scene(c):
    """The ground, a 0.2 m box of 2 kg resting on it at x = 1 and a ball of
    radius 0.25 m at x = -1, z = 2 (fixed)."""
    c.set_gravity((0, 0, -G))
    ground = c.add_plane((0, 0, 1), 0.0)
    box = c.add_box((0.1, 0.1, 0.1), position=(1, 0, 0.1), mass=2.0, restitution=0.0)
    ball = c.add_sphere(0.25, position=(-1, 0, 2), fixed=True)
    return ground, box, ball


def test_ray_cast_answers_the_geometry(client):
    ground, box, ball = scene(client)
    origins = [(1.05, 0.02, 3.0), (-1, 0, 5), (5, 5, 1), (0, 0, -1), (-1, 3, 2)]
    directions = [(0, 0, -1), (0, 0, -2), (1, 0, 0), (0, 0, 1), (0, -1, 0)]
    hits = client.ray_cast(origins, directions, 10.0)
    hit, ids, points, normals, dist = hits
    assert hit.tolist() == [True, True, False, True, True]
    assert ids.tolist() == [box, ball, 0, ground, ball]
    assert dist[0] == pytest.approx(2.8, abs=1e-12)          # the box's top at z = 0.2
    assert points[0] == pytest.approx([1.05, 0.02, 0.2], abs=1e-12)
    assert normals[0] == pytest.approx([0, 0, 1], abs=1e-12)
    assert dist[1] == pytest.approx(2.75, abs=1e-12)          # the ball's top at z = 2.25
    assert dist[3] == 0.0                                     # starts inside the ground
    assert normals[3] == pytest.approx([0, 0, -1])            # against the ray
    assert dist[4] == pytest.approx(2.75, abs=1e-12)
    assert normals[4] == pytest.approx([0, 1, 0], abs=1e-12)
    # the same rays ignoring the box reach the ground; one max distance per ray
    again = client.ray_cast(origins, directions, [10, 10, 10, 10, 2.0], ignore=[box])
    assert again.body_ids[0] == ground and again.distances[0] == pytest.approx(3.0)
    assert not again.hit[4]                                   # 2.75 m is beyond 2 m


@pytest.mark.parametrize("origins,directions,max_distance,words", [
    ([(math.nan, 0, 0)], [(0, 0, 1)], 1.0, "origin is not finite"),
    ([(0, 0, 0)], [(0, 0, 0)], 1.0, "direction has length"),
    ([(0, 0, 0)], [(0, math.inf, 0)], 1.0, "direction is not finite"),
    ([(0, 0, 0)], [(0, 0, 1)], -1.0, "max_distance"),
    ([(0, 0, 0)], [(0, 0, 1)], math.nan, "max_distance"),
])
def test_ray_cast_refuses_garbage(client, origins, directions, max_distance, words):
    with pytest.raises(contactsim.CommandError) as e:
        client.ray_cast(origins, directions, max_distance)
    assert e.value.code == contactsim.reply_t.INVALID_ARGUMENT
    assert "ray 0: " in str(e.value) and words in str(e.value)


def test_ray_cast_refuses_unknown_ignored_bodies_and_bad_shapes(client):
    with pytest.raises(contactsim.CommandError) as e:
        client.ray_cast([(0, 0, 1)], [(0, 0, -1)], 1.0, ignore=[99])
    assert e.value.code == contactsim.reply_t.NOT_FOUND and "99" in str(e.value)
    with pytest.raises(ValueError):
        client.ray_cast([(0, 0, 1, 2)], [(0, 0, -1)], 1.0)
    with pytest.raises(ValueError):
        client.ray_cast([(0, 0, 1), (0, 0, 2)], [(0, 0, -1)], 1.0)


def lidar_fan(n=9):
    """n rays in the body's x-z plane, from straight down to 45 degrees
    forward."""
    a = np.linspace(0.0, math.pi / 4, n)
    return np.stack([np.sin(a), np.zeros(n), -np.cos(a)], axis=1)


def test_lidar_and_contact_sensor_read_the_world(client):
    ground, box, ball = scene(client)
    drone = client.add_sphere(0.05, position=(0.5, 0, 1.0), fixed=True)
    client.add_range_sensor(drone, "lidar", lidar_fan(), 5.0, origin=(0, 0, -0.05))
    client.add_contact_sensor(box, "foot")
    client.step(60)
    s = client.sensors()  # published with the STEP's last STATE, before its reply
    lidar = s.ranges["lidar"]
    assert lidar["body_id"] == drone
    # straight down: the ground 0.95 m below the ray's origin
    assert lidar["hit"][0] and lidar["body_ids"][0] == ground
    assert lidar["distances"][0] == pytest.approx(0.95, abs=1e-9)
    # 45 degrees forward reaches x = 1.5 on the ground, past the box
    assert lidar["body_ids"][-1] == ground
    assert lidar["distances"][-1] == pytest.approx(0.95 * math.sqrt(2), abs=1e-9)
    foot = s.contacts["foot"]
    assert foot["body_id"] == box and foot["num_contacts"] > 0
    assert foot["normal_force"][2] == pytest.approx(2.0 * G, rel=0.01)
    assert np.linalg.norm(foot["friction_force"]) < 0.01 * 2.0 * G
    # removing a body removes its sensors; removing by name, too
    client.remove_body(drone)
    client.step(1)
    s = client.sensors()
    assert "foot" in s.contacts
    client.remove_sensor("foot")
    with pytest.raises(contactsim.CommandError) as e:
        client.remove_sensor("foot")
    assert e.value.code == contactsim.reply_t.NOT_FOUND


def test_sensor_commands_refuse_garbage(client):
    ground, box, ball = scene(client)
    bad = [
        (lambda: client.add_range_sensor(box, "", [(0, 0, 1)], 1.0), "name"),
        (lambda: client.add_range_sensor(box, "a b", [(0, 0, 1)], 1.0), "name"),
        (lambda: client.add_range_sensor(box, "l", [(0, 0, 0)], 1.0), "direction 0"),
        (lambda: client.add_range_sensor(box, "l", [(0, 0, 1)], 0.0), "max_distance"),
        (lambda: client.add_range_sensor(box, "l", [(0, 0, 1)], math.inf), "max_distance"),
        (lambda: client.add_range_sensor(box, "l", [(0, 0, 1)], 1.0, origin=(math.nan, 0, 0)), "origin"),
        (lambda: client.add_range_sensor(99, "l", [(0, 0, 1)], 1.0), "unknown body"),
        (lambda: client.add_contact_sensor(99, "c"), "unknown body"),
    ]
    for call, words in bad:
        with pytest.raises(contactsim.CommandError) as e:
            call()
        assert words in str(e.value), str(e.value)
    client.add_contact_sensor(box, "c")
    with pytest.raises(contactsim.CommandError) as e:
        client.add_contact_sensor(box, "c")
    assert "exists already" in str(e.value)
    # a method that reports no contact forces is refused while the sensor exists
    with pytest.raises(contactsim.CommandError) as e:
        client.set_contact_method("barrier")
    assert "does not report contact forces" in str(e.value)
    client.remove_sensor("c")
    client.set_contact_method("barrier")
    with pytest.raises(contactsim.CommandError) as e:
        client.add_contact_sensor(box, "c")
    assert e.value.code == contactsim.reply_t.FAILED_PRECONDITION
    assert "does not report contact forces" in str(e.value)


def readings(c, steps):
    """The SENSORS message of each of the next `steps` steps, as bytes."""
    got = {}
    remove = c.on_sensors(lambda s: got.__setitem__(s.step, (
        s.ranges["lidar"]["distances"].tobytes(), s.ranges["lidar"]["points"].tobytes(),
        s.contacts["foot"]["normal_force"].tobytes(), s.contacts["foot"]["torque"].tobytes())))
    try:
        c.step(steps)  # SENSORS goes out after each STATE and before the STEP's reply
    finally:
        remove()
    return got


def test_sensor_readings_repeat_bit_for_bit_after_a_rewind(client):
    ground, box, ball = scene(client)
    client.add_sphere(0.1, position=(1.02, 0.01, 0.6), mass=0.5)  # falls on the box
    client.add_range_sensor(box, "lidar", lidar_fan(16) * [-1, 1, -1], 3.0, origin=(0, 0, 0.1))
    client.add_contact_sensor(box, "foot")
    client.step(10)  # REWIND goes back to the state after a step, so not before the first
    first = readings(client, 40)
    client.rewind(client.state().step - 40)
    second = readings(client, 40)
    common = sorted(set(first) & set(second))
    assert len(common) >= 5, (sorted(first), sorted(second))
    for step in common:
        assert first[step] == second[step], step


def test_a_recorded_run_with_sensors_replays_identically(launch, tmp_path):
    server = launch()
    path = tmp_path / "sensors.lcmlog"
    c = server.client
    with LcmRecorder(server.url, server.prefix + "_.*", path) as recorder:
        ground, box, ball = scene(c)
        c.add_range_sensor(box, "lidar", lidar_fan(), 3.0)
        c.add_contact_sensor(box, "foot")
        recorder.sync()
        c.step(30)
        recorder.sync()
        c.ray_cast([(1, 0, 2)], [(0, 0, -1)], 5.0)
        c.remove_sensor("lidar")
        c.step(10)
        recorder.sync()
    out = subprocess.run([str(SERVER_BIN), "--config", str(CONFIG), "--scene", str(server.scene),
                          "--prefix", server.prefix, "--replay", str(path)],
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stdout + out.stderr
    assert out.stdout.startswith("identical: "), out.stdout


def test_both_clis_cast_a_ray_alike(server):
    from test_cli import cli
    from test_cli_parity import CTL
    ground = server.client.add_plane((0, 0, 1), 0.0)
    expected = "hit body %d distance 5 point 0 0 0 normal 0 0 1" % ground
    r = cli(server, "ray", "0", "0", "5", "0", "0", "-3")
    assert r.returncode == 0 and r.stdout.strip() == expected, r.stdout + r.stderr
    assert cli(server, "ray", "0", "0", "5", "0", "0", "1").stdout.strip() == "miss"
    r = cli(server, "ray", "0", "0", "5", "0", "0", "0")
    assert r.returncode == 1 and "direction has length" in r.stderr, r.stdout + r.stderr
    if CTL.exists():
        r = subprocess.run([str(CTL), "--lcm-url", server.url, "--prefix", server.prefix, "ray", "0", "0", "5", "0",
                            "0", "-3"], capture_output=True, text=True, timeout=30)
        assert r.returncode == 0 and r.stdout.strip() == expected, r.stdout + r.stderr
