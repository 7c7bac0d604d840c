"""Re-simulation of a recorded run of Drake's arm driver: a real server
(config/iiwa_driver.pbtxt) is driven by Drake's own IiwaCommandSender
(examples/drake_arm_controller.py, a sweep, as test_iiwa_driver.py runs it)
in REALTIME while the stock lcm-logger records the server's channels and
IIWA_COMMAND. The server answers each accepted arm command on REPLY with the
step it applied at (docs/actuators.md), so ``contactsim-server --replay LOG``
re-applies every command at that step and agrees with every logged STATE
bit for bit; a log with one command changed diverges.
Needs the PyPI wheel ``drake``; skipped without it."""
import subprocess

import lcm
import pytest

from conftest import REPO, SERVER_BIN
from lcm_recorder import LcmRecorder

pytest.importorskip("pydrake", reason="the PyPI wheel drake is not installed (pip install drake==1.51.1)")
from drake import lcmt_iiwa_command  # noqa: E402

import contactsim  # noqa: E402
from drake_arm import run_controller  # noqa: E402

CONFIG = REPO / "config" / "iiwa_driver.pbtxt"
SCENE = REPO / "config" / "scenes" / "arm_ground.pbtxt"
ARM = "IIWA_COMMAND"
RECORD_TRIES = 3  # a log that lost a message on UDP is recorded again


def events(path, prefix):
    """(kind, decoded) for the arm's commands, REPLYs and STATEs, in log order."""
    out = []
    for e in lcm.EventLog(str(path), "r"):
        if e.channel == ARM:
            out.append(("ARM", lcmt_iiwa_command.decode(e.data)))
        elif e.channel == prefix + "_REPLY":
            out.append(("REPLY", contactsim.reply_t.decode(e.data)))
        elif e.channel == prefix + "_STATE":
            out.append(("STATE", contactsim.state_t.decode(e.data)))
    return out


def arm_commands_placed(log):
    """Every arm command has its OK reply after it and every such reply its
    command before it: the logger (UDP) can lose either alone."""
    waiting = set()
    for kind, m in log:
        if kind == "ARM":
            waiting.add(m.utime)
        elif kind == "REPLY" and m.client_id == ARM:
            if m.request_id not in waiting or m.code != contactsim.reply_t.OK:
                return False
            waiting.discard(m.request_id)
    return not waiting


def record(launch, tmp_path):
    for attempt in range(RECORD_TRIES):
        server = launch(scene=SCENE, config=CONFIG)
        path = tmp_path / ("arm%d.lcmlog" % attempt)
        # the probe channel (prefix + "_|IIWA_COMMANDRECORDER_PROBE") matches the first alternative
        with LcmRecorder(server.url, server.prefix + "_.*|" + ARM, path):
            server.client.set_mode("realtime")
            server.client.resume()
            run_controller(server, "iiwa", 1.5)
            server.client.pause()
        log = events(path, server.prefix)
        if arm_commands_placed(log) and sum(k == "ARM" for k, _ in log) >= 20:
            return server, path, log
    pytest.fail("every recording lost an arm command or its reply on UDP")


def replay(server, log):
    return subprocess.run([str(SERVER_BIN), "--config", str(CONFIG), "--scene", str(SCENE), "--prefix", server.prefix,
                           "--replay", str(log)], capture_output=True, text=True, timeout=300)


# Verifies that the replay feeds every logged arm command at its step and
# matches every logged STATE's hash, and that a log whose tenth command
# asks 0.01 rad more of joint 3 diverges at the first STATE after it.
def test_replay_reapplies_the_arm_commands(launch, tmp_path):
    server, path, log = record(launch, tmp_path)
    commands = sum(k == "ARM" for k, _ in log)
    out = replay(server, path)
    assert out.returncode == 0, out.stdout + out.stderr
    assert out.stdout.startswith("identical: "), out.stdout
    assert int(out.stdout.split()[1]) >= 20, out.stdout  # STATE messages compared
    fed = int(out.stdout.split("\n")[1].split()[0])
    assert fed >= commands, out.stdout  # the arm's commands and the client's

    tampered = tmp_path / "tampered.lcmlog"
    src, dst = lcm.EventLog(str(path), "r"), lcm.EventLog(str(tampered), "w", overwrite=True)
    seen, target = 0, None
    for e in src:
        data = e.data
        if e.channel == ARM:
            seen += 1
            if seen == 10:
                m = lcmt_iiwa_command.decode(data)
                m.joint_position = [q + (0.01 if i == 3 else 0.0) for i, q in enumerate(m.joint_position)]
                data, target = m.encode(), m.utime
        dst.write_event(e.timestamp, e.channel, data)
    src.close()
    dst.close()
    applied = [m.step for k, m in log if k == "REPLY" and m.client_id == ARM and m.request_id == target][0]
    first_after = min(m.step for k, m in log if k == "STATE" and m.step > applied)
    out = replay(server, tampered)
    assert out.returncode == 2, out.stdout + out.stderr
    assert out.stdout.startswith("divergence at step %d: " % first_after), out.stdout
    # the last command fed before that STATE: the changed one, or a later one
    # applied before the same STATE (STATE is decimated in REALTIME)
    fed_last = int(out.stdout.split('IIWA_COMMAND from "IIWA_COMMAND" #')[1].split()[0])
    assert target <= fed_last, out.stdout
