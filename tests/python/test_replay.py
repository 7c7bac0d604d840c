"""Re-simulation of a recorded run: a real server is recorded with lcm-logger
while a client drives it (commands, STEPs, a realtime stretch with commands
landing between decimated STATEs, a lockstep controller, snapshot and
rewind, collision filters given at ADD and by SET_FILTER);
``contactsim-server --replay LOG`` must agree at every logged STATE,
and must name the first divergent step of a tampered log."""
import subprocess
import time

import lcm
import pytest

import contactsim

from conftest import CONFIG, SERVER_BIN
from lcm_recorder import LcmRecorder

RECORD_TRIES = 3  # a log that lost a message on UDP is recorded again


def drive(c, drain):
    """The recorded run; drain() returns once the logger has written all
    published so far. The logger queues at most 30 messages and a STEP
    publishes a burst of STATEs: drained before the long STEP, so that its
    burst and reply fit, and after each STEP, so that the next command is
    not lost to a full queue while its later reply is logged."""
    c.set_gravity((0, 0, -9.81))
    c.add_plane((0, 0, 1), 0.0)
    ball = c.add_sphere(0.1, position=(0, 0, 0.5), mass=1.0, restitution=0.5)
    box = c.add_box((0.1, 0.1, 0.1), position=(0.5, 0, 0.3), mass=2.0, collision_category=4)
    bob = c.add_sphere(0.05, position=(1.5, 0, 1.0), mass=0.5)
    c.add_joint("distance", bob, None, anchor=(1.5, 0, 1.5))
    drain()
    c.step(60)
    drain()
    c.set_contact_method("impulse", iterations=40)
    c.set_filter(ball, collision_category=2, collision_mask=1)  # the ball passes through the box
    # realtime: these land at whatever step the server is at, between the
    # 60 Hz STATEs; their replies say which
    c.set_mode("realtime")
    c.resume()
    for i in range(5):
        time.sleep(0.03)
        c.apply_impulse(ball, (0.2, 0.0, 0.1 * i))
    c.pause()
    c.snapshot("a")
    c.step(30)
    drain()
    with contactsim.Controller(c, lambda s: {box: (3.0, 0.0, 0.0)}) as ctl:
        c.set_mode("lockstep")
        c.resume()
        ctl.wait_for_step(c.state().step + 20, timeout=20)
        c.pause()
    c.set_mode("free_run")
    c.rewind(c.state().step - 10)
    c.step(15)
    return ball


COMMANDS = ("BODY_CMD", "SCENE_CMD", "JOINT_CMD")


def logged(path, prefix):
    """The log's commands, replies, inputs and STATEs in log order, as
    (channel suffix, decoded message)."""
    events = []
    for e in lcm.EventLog(str(path), "r"):
        ch = e.channel[len(prefix) + 1:]
        if ch in COMMANDS + ("REPLY", "INPUT", "STATE"):
            events.append((ch, getattr(contactsim, ch.lower() + "_t").decode(e.data)))
    return events


def every_command_fed(events):
    """The replay feeds a command when its OK reply follows it in the log
    (log_replay.h), so every logged command needs a reply after it and every
    OK reply needs its command before it: the logger can lose either one
    alone, and an OK reply whose command was lost is skipped silently.
    (Lockstep inputs get only error replies; a refused command changed nothing.)"""
    waiting = set()
    for ch, m in events:
        if ch in COMMANDS:
            waiting.add((m.client_id, m.request_id))
        elif ch == "REPLY":
            key = (m.client_id, m.request_id)
            if key not in waiting and m.code == contactsim.reply_t.OK:
                return False
            waiting.discard(key)
    return not waiting


def no_request_id_lost(events, client):
    """The client's request ids count up from 1 by one per command or input
    (a resend keeps its id), and the recording spans all it used: a missing
    id is a command lost together with its reply (first, last or between),
    or an input. The client keeps no public count of the ids it used."""
    ids = {m.request_id for ch, m in events if ch != "STATE" and m.client_id == client.client_id}
    return ids == set(range(1, client._request_id + 1))


def every_input_logged(events):
    """Every step whose STATE shows applied lockstep inputs has an INPUT in the log."""
    input_steps = {m.step for ch, m in events if ch == "INPUT"}
    return all(m.step in input_steps for ch, m in events if ch == "STATE" and m.input_digest != 0)


def complete(path, prefix, client):
    """True if the logger lost nothing the replay needs of a run that
    `client` drove, all of it recorded."""
    events = logged(path, prefix)
    return every_command_fed(events) and no_request_id_lost(events, client) and every_input_logged(events)


def replay(server, log, scene=None):
    return subprocess.run([str(SERVER_BIN), "--config", str(CONFIG), "--scene", str(scene or server.scene),
                           "--prefix", server.prefix, "--replay", str(log)],
                          capture_output=True, text=True, timeout=120)


def record(launch, tmp_path):
    for attempt in range(RECORD_TRIES):
        server = launch()
        path = tmp_path / ("run%d.lcmlog" % attempt)
        with LcmRecorder(server.url, server.prefix + "_.*", path) as recorder:
            ball = drive(server.client, recorder.sync)
        if complete(path, server.prefix, server.client):
            return server, path, ball
    pytest.fail("every recording lost a command, a reply or an input on UDP")


def test_replay_of_a_recorded_run_is_identical_and_a_tampered_one_is_not(launch, tmp_path):
    server, path, ball = record(launch, tmp_path)
    out = replay(server, path)
    assert out.returncode == 0, out.stdout + out.stderr
    assert out.stdout.startswith("identical: ")
    assert int(out.stdout.split()[1]) >= 50  # STATE messages compared

    # the third impulse made 10% stronger: reported at the first STATE after its reply
    tampered = tmp_path / "tampered.lcmlog"
    src, dst = lcm.EventLog(str(path), "r"), lcm.EventLog(str(tampered), "w", overwrite=True)
    impulses, target, expected_step = 0, None, None
    for e in src:
        data, ch = e.data, e.channel[len(server.prefix) + 1:]
        if ch == "BODY_CMD":
            m = contactsim.body_cmd_t.decode(data)
            if m.op == contactsim.body_cmd_t.APPLY_IMPULSE:
                impulses += 1
                if impulses == 3:
                    m.impulse = [v * 1.1 for v in m.impulse]
                    data, target = m.encode(), (m.client_id, m.request_id)
        elif ch == "REPLY" and target is not None and expected_step is None:
            m = contactsim.reply_t.decode(data)
            if (m.client_id, m.request_id) == target:
                expected_step = "after"
        elif ch == "STATE" and expected_step == "after":
            expected_step = contactsim.state_t.decode(data).step
        dst.write_event(e.timestamp, e.channel, data)
    src.close()
    dst.close()
    assert isinstance(expected_step, int)
    out = replay(server, tampered)
    assert out.returncode == 2, out.stdout + out.stderr
    assert out.stdout.startswith("divergence at step %d: logged state_hash " % expected_step), out.stdout
    assert "impulse on body %d" % ball in out.stdout


def test_replay_with_another_gravity_diverges_at_the_first_step(launch, tmp_path):
    server, path, _ = record(launch, tmp_path)
    scene = tmp_path / "other_gravity.pbtxt"
    scene.write_text("gravity { z: -9.80 }\n")
    # the run sets gravity by command first; a replay from the other scene
    # still agrees until then, so tamper with nothing but start the replay
    # from a log without that command
    trimmed = tmp_path / "no_gravity_cmd.lcmlog"
    src, dst = lcm.EventLog(str(path), "r"), lcm.EventLog(str(trimmed), "w", overwrite=True)
    for e in src:
        if e.channel == server.prefix + "_SCENE_CMD":
            m = contactsim.scene_cmd_t.decode(e.data)
            if m.op == contactsim.scene_cmd_t.SET_GRAVITY:
                continue
        dst.write_event(e.timestamp, e.channel, e.data)
    src.close()
    dst.close()
    same = replay(server, trimmed)  # the empty scene's gravity is the command's
    assert same.returncode == 0, same.stdout + same.stderr
    out = replay(server, trimmed, scene=scene)
    assert out.returncode == 2, out.stdout + out.stderr
    # bodies at rest hash alike at step 0; the first stepped STATE differs
    step = int(out.stdout.split("divergence at step ")[1].split(":")[0])
    assert 0 < step <= 60, out.stdout
