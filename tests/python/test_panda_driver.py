"""Drake's own Panda driver systems drive contactsim's simulated Franka Panda.

The server runs config/panda_driver.pbtxt (PyPI's pybullet_data Panda on a
fixed base); the controller is examples/drake_arm_controller.py --arm panda,
a Drake diagram of PandaCommandSender (position and torque mode) and
PandaStatusReceiver over LCM, in a process of its own, as a user runs it
(docs/actuators.md, "Drake's arm driver"). Bad commands are Drake's own
lcmt_panda_command published directly. Needs the PyPI wheel ``drake``
(requirements.txt); skipped without it.
"""
import lcm
import numpy as np
import pytest

from conftest import REPO

pytest.importorskip("pydrake", reason="the PyPI wheel drake is not installed (pip install drake==1.51.1)")
from drake import lcmt_panda_command, lcmt_panda_status  # noqa: E402

import contactsim  # noqa: E402
from drake_arm import Tap, run_controller  # noqa: E402

CONFIG = REPO / "config" / "panda_driver.pbtxt"
SCENE = REPO / "config" / "scenes" / "arm_ground.pbtxt"
JOINTS = 7
PERIOD_US = 1000          # the Panda's control cycle: 1 kHz
HOLD_TOLERANCE = 1e-3     # rad: the arm held at a commanded pose
POSE = [0.2, -0.6, -0.1, -2.2, 0.1, 1.7, 0.6]  # rad, within every joint's limits, near Franka's ready pose
POSITION, VELOCITY, TORQUE = (lcmt_panda_status.CONTROL_MODE_POSITION, lcmt_panda_status.CONTROL_MODE_VELOCITY,
                              lcmt_panda_status.CONTROL_MODE_TORQUE)


@pytest.fixture
def arm(launch):
    server = launch(scene=SCENE, config=CONFIG)
    server.client.set_mode("realtime")
    server.client.resume()
    return server


@pytest.fixture
def tap(arm):
    t = Tap(arm, "PANDA_STATUS", lcmt_panda_status)
    yield t
    t.close()


def command(utime, mode, position=(), velocity=(), torque=()):
    m = lcmt_panda_command()
    m.utime = utime
    m.num_joint_position, m.joint_position = len(position), list(position)
    m.num_joint_velocity, m.joint_velocity = len(velocity), list(velocity)
    m.num_joint_torque, m.joint_torque = len(torque), list(torque)
    m.control_mode_expected = mode
    return m


# Verifies that the status comes every 1 ms of simulated time (utime steps
# of 1000 us), for the Panda's seven joints, stamped on the robot's clock
# alike, in position mode while the driver holds the arm.
def test_status_at_the_drivers_rate(arm, tap):
    assert tap.wait(lambda: len(tap.statuses) >= 500), "fewer than 500 statuses in 10 s\n" + arm.log()
    s = list(tap.statuses)
    assert all(m.num_joints == JOINTS for m in s)
    assert all(m.robot_utime == m.utime and m.control_mode == POSITION for m in s)
    steps = np.diff([m.utime for m in s])
    assert np.all(steps % PERIOD_US == 0) and np.all(steps > 0), steps
    # a multicast datagram may be lost; most arrive
    assert np.mean(steps == PERIOD_US) > 0.9, steps


# Verifies that Drake's PandaCommandSender holds the arm at a commanded pose
# to 1 mrad, at rest, read through PandaStatusReceiver, with its zero
# feed-forward torque and no external torque.
def test_drake_holds_the_arm_at_a_commanded_pose(arm):
    report = run_controller(arm, "panda", 4.0, "--pose", *POSE)
    assert report["position_commanded"] == POSE
    error = np.max(np.abs(np.subtract(report["position_measured"], POSE)))
    assert error < HOLD_TOLERANCE, report
    assert np.max(np.abs(report["velocity_measured"])) < 1e-2, report
    assert report["torque_commanded"] == [0.0] * JOINTS
    assert np.max(np.abs(report["torque_external"])) < 1e-9, report


# Verifies that commands Drake's driver would not take are refused with the
# reason (a reply named by the channel and its utime), leave the commanded
# position as it was, and that the driver goes on publishing: a mode that
# is none, arrays that disagree with the mode, a wrong count, a NaN.
def test_bad_commands_are_refused(arm, tap):
    assert tap.wait(lambda: tap.statuses), arm.log()
    before = list(tap.statuses[-1].joint_position_desired)
    pub = lcm.LCM(arm.url)
    nan = [0.1, 0.1, float("nan"), 0.1, 0.1, 0.1, 0.1]
    bad = [(101, command(101, 8, position=[0.1] * JOINTS), "control_mode_expected 8 is not a control mode"),
           (102, command(102, POSITION | TORQUE, position=[0.1] * JOINTS), "asks for joint_torque"),
           (103, command(103, VELOCITY, velocity=[0.1] * 6), "joint_velocity has 6 entries; the arm has 7 joints"),
           (104, command(104, POSITION, position=nan), "joint_position[2] is nan")]
    for utime, m, says in bad:
        pub.publish("PANDA_COMMAND", m.encode())
        r = tap.reply_to(utime, arm)
        assert r.client_id == "PANDA_COMMAND"
        assert r.code == contactsim.reply_t.INVALID_ARGUMENT
        assert says in r.message, r.message
    n = len(tap.statuses)
    assert tap.wait(lambda: len(tap.statuses) > n + 50), arm.log()
    assert list(tap.statuses[-1].joint_position_desired) == before
    assert tap.statuses[-1].control_mode == POSITION
