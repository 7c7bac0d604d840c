"""Drake's own iiwa driver systems drive contactsim's simulated iiwa.

The server runs config/iiwa_driver.pbtxt (PyPI's pybullet_data iiwa on a
fixed base); the controller is examples/drake_arm_controller.py --arm iiwa,
a Drake diagram of IiwaCommandSender and IiwaStatusReceiver over LCM, in a process
of its own, as a user runs it (docs/actuators.md, "Drake's arm driver").
Needs the PyPI wheel ``drake`` (requirements.txt); skipped without it.
"""
import lcm
import numpy as np
import pytest

from conftest import REPO

pytest.importorskip("pydrake", reason="the PyPI wheel drake is not installed (pip install drake==1.51.1)")
from drake import lcmt_iiwa_command, lcmt_iiwa_status  # noqa: E402

import contactsim  # noqa: E402
from drake_arm import Tap, run_controller  # noqa: E402

CONFIG = REPO / "config" / "iiwa_driver.pbtxt"
SCENE = REPO / "config" / "scenes" / "arm_ground.pbtxt"
JOINTS = 7
PERIOD_US = 5000          # Drake's driver: 200 Hz
HOLD_TOLERANCE = 1e-3     # rad: the arm held at a commanded pose
POSE = [0.3, 0.5, -0.2, -1.0, 0.2, 0.6, 0.1]  # rad, within every joint's limits


@pytest.fixture
def arm(launch):
    server = launch(scene=SCENE, config=CONFIG)
    server.client.set_mode("realtime")
    server.client.resume()
    return server


@pytest.fixture
def tap(arm):
    t = Tap(arm, "IIWA_STATUS", lcmt_iiwa_status)
    yield t
    t.close()


# Verifies that the status comes every 5 ms of simulated time (utime steps
# of 5000 us), for the iiwa's seven joints.
def test_status_at_the_drivers_rate(arm, tap):
    assert tap.wait(lambda: len(tap.statuses) >= 100), "fewer than 100 statuses in 10 s\n" + arm.log()
    s = list(tap.statuses)
    assert all(m.num_joints == JOINTS for m in s)
    steps = np.diff([m.utime for m in s])
    assert np.all(steps % PERIOD_US == 0) and np.all(steps > 0), steps
    # a multicast datagram may be lost; most arrive
    assert np.mean(steps == PERIOD_US) > 0.9, steps


# Verifies that Drake's IiwaCommandSender's position and feed-forward torque
# come back through IiwaStatusReceiver as the commanded position and torque.
def test_feedforward_torque_shows_in_commanded_torque(arm):
    torque = [0.5, -1.0, 1.5, -2.0, 2.5, -3.0, 3.5]
    report = run_controller(arm, "iiwa", 1.0, "--pose", *POSE, "--torque", *torque)
    assert report["torque_commanded"] == torque
    assert report["position_commanded"] == POSE
    assert report["torque_external"] == [0.0] * JOINTS
    assert report["time_measured"] > 0


# Verifies that a command with six positions, or with a NaN, is refused with
# the reason (a reply named by the channel and its utime, STATUS's
# last_error), leaves the commanded position as it was, and that the driver
# goes on publishing.
def test_bad_commands_are_refused(arm, tap):
    assert tap.wait(lambda: tap.statuses), arm.log()
    before = list(tap.statuses[-1].joint_position_commanded)
    pub = lcm.LCM(arm.url)
    bad = [(101, [0.1] * 6, "joint_position has 6 entries; the arm has 7 joints"),
           (102, [0.1, 0.1, float("nan"), 0.1, 0.1, 0.1, 0.1], "joint_position[2] is nan")]
    for utime, positions, says in bad:
        m = lcmt_iiwa_command()
        m.utime = utime
        m.num_joints = len(positions)
        m.joint_position = positions
        m.num_torques = 0
        m.joint_torque = []
        pub.publish("IIWA_COMMAND", m.encode())
        r = tap.reply_to(utime, arm)
        assert r.client_id == "IIWA_COMMAND"
        assert r.code == contactsim.reply_t.INVALID_ARGUMENT
        assert says in r.message
    n = len(tap.statuses)
    assert tap.wait(lambda: len(tap.statuses) > n + 10), arm.log()
    assert list(tap.statuses[-1].joint_position_commanded) == before
    # STATUS comes once a second of wall-clock time
    assert tap.wait(lambda: "joint_position[2] is nan" in getattr(arm.client.status(), "last_error", "")), \
        arm.client.status()


# Verifies that Drake's controller holds the arm at a commanded pose to
# 1 mrad, at rest. Needs the joint drives' physics (World::SetJointActuator
# acting in the contact methods): skipped, with the reason, on a server
# whose drives do not move the arm at all.
def test_drake_holds_the_arm_at_a_commanded_pose(arm):
    report = run_controller(arm, "iiwa", 4.0, "--pose", *POSE)
    moved = np.max(np.abs(np.subtract(report["position_measured"], report["start_position"])))
    if moved == 0.0:
        pytest.skip("the joint drives did not move the arm at all: this build's contact methods do not apply "
                    "joint actuators (World::SetJointActuator) yet")
    error = np.max(np.abs(np.subtract(report["position_measured"], POSE)))
    assert error < HOLD_TOLERANCE, report
    assert np.max(np.abs(report["velocity_estimated"])) < 1e-2, report
