"""Recording a real server with the stock lcm-logger, playing the log back
with lcm-logplayer, reading it with contactsim.logread and plotting it with
``python -m contactsim.plot``."""
import os
import subprocess
import sys
import time

import lcm
import numpy as np
import pytest

import contactsim
from contactsim.logread import read_log

from conftest import REPO, unique_endpoint
from lcm_recorder import LcmRecorder, lcm_tool

G = 9.81
DT = 1.0 / 240.0
CHANNELS = ("BODY_CMD", "SCENE_CMD", "JOINT_CMD", "INPUT", "REPLY", "STATE", "CONTACTS", "STATUS", "ACTUATOR_CMD",
            "JOINT_STATE")


def record_every_channel(server, path):
    """Drives the server through every command channel, with a lockstep
    controller, for at least 2.2 s (STATUS is a 1 Hz heartbeat); returns the
    resting sphere's mass."""
    c = server.client
    mass = 2.0
    with LcmRecorder(server.url, server.prefix + "_.*", path):
        start = time.monotonic()
        c.set_gravity((0, 0, -G))
        c.add_plane((0, 0, 1), 0.0)
        ball = c.add_sphere(0.1, position=(0, 0, 0.1), mass=mass, restitution=0.0)
        bob = c.add_box((0.05, 0.05, 0.05), position=(1, 0, 1.5), mass=1.0)
        c.add_joint("distance", bob, None, anchor=(1, 0, 2))
        arm = c.add_box((0.05, 0.05, 0.2), position=(-1, 0, 1.3), mass=1.0)
        hinge = c.add_joint("hinge", arm, None, anchor=(-1, 0, 1.5), axis=(0, 1, 0))
        c.set_joint_actuator(hinge, target_position=0.3, kp=50.0, kd=5.0)
        c.step(240)
        with contactsim.Controller(c, lambda s: {ball: (0.0, 0.0, 0.0)}) as ctl:
            c.set_mode("lockstep")
            c.resume()
            ctl.wait_for_step(c.state().step + 24, timeout=20)
            c.pause()
        time.sleep(max(0.0, 2.2 - (time.monotonic() - start)))
    return mass


def play_back(path, url, expected):
    """Plays the log with lcm-logplayer on ``url`` and returns what arrived as
    {channel: [payload, ...]}; plays it again (up to 3 times) while a channel
    of ``expected`` is missing, since UDP may drop a lone message."""
    tool = lcm_tool("lcm-logplayer")
    if tool is None:
        pytest.skip("lcm-logplayer is not installed (make deps)")
    got = {}
    lc = lcm.LCM(url)
    lc.subscribe(".*", lambda ch, data: got.setdefault(ch, []).append(data))
    for _ in range(3):
        player = subprocess.Popen([tool, "-s", "4", "--lcm-url=" + url, str(path)], stdout=subprocess.DEVNULL,
                                  stderr=subprocess.STDOUT)
        deadline = time.monotonic() + 60
        while player.poll() is None and time.monotonic() < deadline:
            lc.handle_timeout(50)
        if player.poll() is None:
            player.kill()
        player.wait()
        end = time.monotonic() + 0.5  # the last datagrams
        while time.monotonic() < end:
            lc.handle_timeout(50)
        if all(ch in got for ch in expected):
            break
    return got


def test_every_channel_is_recorded_read_back_and_played_back(server, tmp_path):
    path = tmp_path / "run.lcmlog"
    mass = record_every_channel(server, path)

    log = read_log(path)
    expected = [server.prefix + "_" + ch for ch in CHANNELS]
    assert log.prefix == server.prefix
    for ch in expected:
        assert log.channels.get(ch, 0) > 0, "%s missing from the log: %s" % (ch, log.channels)
    assert len(log.time) > 0 and np.all(np.diff(log.step) >= 0)
    assert log.position.shape == (len(log.time), 4, 3) and log.orientation.shape[2] == 4
    assert log.joints.names == ["2"] and log.joints.position.shape == (len(log.joints.time), 1)
    assert len(log.status.step) >= 2 and log.status.mode[-1] == "lockstep"

    # the sphere rests on the plane: the contact carries its weight (impulse
    # m g dt per step, reported as the mean force m g)
    c = log.contacts
    assert c.count[-1] >= 1 and c.value_kind[-1] == "impulse"
    assert c.total_normal_force[-1] == pytest.approx(mass * G, rel=0.02)
    assert c.max_depth[-1] < 0.002  # within the impulse method's slop of 1 mm (+ one step of sinking)
    assert len(c.frame) == int(c.count.sum())

    # played back on another multicast port: every channel, byte for byte
    url2, _ = unique_endpoint("PLAY")
    played = play_back(path, url2, expected)
    logged = {}
    for event in lcm.EventLog(str(path), "r"):
        logged.setdefault(event.channel, set()).add(event.data)
    for ch in expected:
        assert ch in played, "%s not played back: %s" % (ch, sorted(played))
        assert set(played[ch]) <= logged[ch]


def test_free_fall_energies_and_plots(server, tmp_path):
    """A 2 kg sphere dropped from h0 = 1 m: before impact (step 96, z > 0.2 m)
    KE = m (g t)^2 / 2 and KE + PE = m g h0, up to semi-implicit Euler's
    first-order loss m g^2 dt t / 2; then it lands, so the plots show contacts."""
    c = server.client
    m, h0 = 2.0, 1.0
    path = tmp_path / "fall.lcmlog"
    with LcmRecorder(server.url, server.prefix + "_.*", path) as recorder:
        c.set_gravity((0, 0, -G))
        c.add_plane((0, 0, 1), 0.0, restitution=0.0)
        ball = c.add_sphere(0.1, position=(0, 0, h0), mass=m, restitution=0.0)
        # in bursts of 2 STATEs, each drained into the file before the next:
        # lcm-logger keeps only 30 undelivered messages and, descheduled on a
        # loaded machine, loses what a long STEP publishes meanwhile
        for _ in range(240 // 8):
            c.step(8)
            recorder.sync()
    log = read_log(path, progress=True)
    col = log.body_index[ball]
    before = (log.step <= 96) & ~np.isnan(log.position[:, col, 2])
    assert before.sum() >= 20  # STATE at 60 Hz of simulated time: every 4th step
    t = log.time[before]
    assert np.allclose(t, log.step[before] * DT, rtol=1e-12, atol=1e-12)
    ke, pe = log.kinetic_energy[before], log.potential_energy[before]
    assert ke == pytest.approx(0.5 * m * (G * t) ** 2, rel=1e-9, abs=1e-12)
    # the energies agree with the logged poses and velocities
    z, vz = log.position[before, col, 2], log.linear_velocity[before, col, 2]
    assert pe == pytest.approx(m * G * z, rel=1e-12)
    assert ke == pytest.approx(0.5 * m * vz ** 2, rel=1e-9, abs=1e-12)
    loss = m * G * h0 - (ke + pe)
    assert np.all(loss >= -1e-9)
    assert np.all(loss <= 0.5 * m * G ** 2 * DT * t * (1 + 1e-6) + 1e-9)
    assert log.step[-1] == 240  # the recorder's exit barrier kept the last STATE
    assert log.contacts.count.max() >= 1  # it landed

    out = tmp_path / "plots"
    env = dict(os.environ, PYTHONPATH=str(REPO / "clients" / "python"))
    run = subprocess.run([sys.executable, "-m", "contactsim.plot", str(path), "-o", str(out)],
                         capture_output=True, text=True, timeout=120, env=env)
    assert run.returncode == 0, run.stdout + run.stderr
    for name in ("energy.png", "penetration.png", "contacts.png", "force.png"):
        png = out / name
        assert png.exists() and str(png) in run.stdout
        with open(png, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n"
        assert png.stat().st_size > 5000  # axes, labels and a curve, not an empty canvas


def test_plot_reports_a_missing_log(tmp_path):
    env = dict(os.environ, PYTHONPATH=str(REPO / "clients" / "python"))
    run = subprocess.run([sys.executable, "-m", "contactsim.plot", str(tmp_path / "nope.lcmlog"), "-o",
                          str(tmp_path / "out")], capture_output=True, text=True, timeout=60, env=env)
    assert run.returncode == 1 and "cannot read" in run.stderr


def test_a_state_of_another_layout_is_named_not_misread(tmp_path):
    """A log recorded by a contactsim whose state_t had no joint block: its
    STATE's fingerprint differs, and read_log says so instead of misreading
    it (docs/protocol.md, "State")."""
    m = contactsim.state_t()
    m.step, m.time = 3, 0.01
    new = m.encode()
    old = bytes([new[0] ^ 0x5A]) + new[1:-4]   # another fingerprint, no num_joints
    path = tmp_path / "old.lcmlog"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    log.write_event(0, "CONTACTSIM_STATE", old)
    log.close()
    with pytest.raises(ValueError, match="another version of contactsim") as e:
        read_log(path, prefix="CONTACTSIM")
    assert "CONTACTSIM_STATE" in str(e.value)


def test_joint_trajectories_come_from_state(tmp_path):
    """read_log's joints are STATE's joint blocks, named by JOINT_STATE
    where the log has one and by id otherwise."""
    path = tmp_path / "joints.lcmlog"
    log = lcm.EventLog(str(path), "w", overwrite=True)
    js = contactsim.joint_state_t()
    js.step, js.num_joints, js.joint_ids, js.model_ids, js.names = 1, 1, [4], [1], ["elbow"]
    js.positions, js.velocities, js.efforts = [0.5], [0.25], [2.0]
    log.write_event(0, "CONTACTSIM_JOINT_STATE", js.encode())
    for step in (1, 2):
        m = contactsim.state_t()
        m.step, m.time = step, 0.01 * step
        m.num_joints, m.joint_ids, m.joint_model_ids = 2, [4, 9], [1, 0]
        m.joint_positions, m.joint_velocities, m.joint_efforts = [0.5 * step, 1.0], [0.25, 0.0], [2.0, 0.0]
        log.write_event(step, "CONTACTSIM_STATE", m.encode())
    log.close()
    j = read_log(path, prefix="CONTACTSIM").joints
    assert list(j.step) == [1, 2] and list(j.joint_ids) == [4, 9]
    assert j.names == ["elbow", "9"] and list(j.model_ids) == [1, 0]
    np.testing.assert_array_equal(j.position, [[0.5, 1.0], [1.0, 1.0]])
