"""Drake's own WSG systems drive the Panda's hand over the Schunk WSG protocol.

The server runs config/wsg_driver.pbtxt (PyPI's pybullet_data Panda on a
fixed base, its arm under Drake's Panda protocol and its two prismatic
fingers under Drake's Schunk WSG protocol, docs/actuators.md, "Drake's
Schunk WSG gripper"). The commands are built by Drake's
SchunkWsgCommandSender and the statuses read by its SchunkWsgStatusReceiver,
both from pydrake.manipulation; a bad command is Drake's own
lcmt_schunk_wsg_command published directly. Needs the PyPI wheel ``drake``
(requirements.txt); skipped without it.
"""
import lcm
import numpy as np
import pytest

from conftest import REPO

pytest.importorskip("pydrake", reason="the PyPI wheel drake is not installed (pip install drake==1.51.1)")
from drake import lcmt_schunk_wsg_command, lcmt_schunk_wsg_status  # noqa: E402
from pydrake.manipulation import SchunkWsgCommandSender, SchunkWsgStatusReceiver  # noqa: E402

import contactsim  # noqa: E402
from drake_arm import Tap  # noqa: E402

CONFIG = REPO / "config" / "wsg_driver.pbtxt"
SCENE = REPO / "config" / "scenes" / "arm_ground.pbtxt"
PERIOD_US = 50000       # Drake's kSchunkWsgLcmStatusPeriod: 20 Hz
SETTLED = 1e-4          # m: the fingers at rest at a commanded separation


@pytest.fixture
def hand(launch):
    server = launch(scene=SCENE, config=CONFIG)
    server.client.set_mode("realtime")
    server.client.resume()
    return server


@pytest.fixture
def tap(hand):
    t = Tap(hand, "SCHUNK_WSG_STATUS", lcmt_schunk_wsg_status)
    yield t
    t.close()


def sender_command(position_m, force_n, time_s):
    """The lcmt_schunk_wsg_command Drake's SchunkWsgCommandSender makes."""
    sender = SchunkWsgCommandSender()
    context = sender.CreateDefaultContext()
    context.SetTime(time_s)
    sender.get_position_input_port().FixValue(context, [position_m])
    sender.get_force_limit_input_port().FixValue(context, [force_n])
    return sender.get_output_port(0).Eval(context)


def received(status):
    """Drake's SchunkWsgStatusReceiver's reading: (separation m, its rate m/s), force N."""
    receiver = SchunkWsgStatusReceiver()
    context = receiver.CreateDefaultContext()
    receiver.get_input_port(0).FixValue(context, status)
    return receiver.get_state_output_port().Eval(context), receiver.get_force_output_port().Eval(context)[0]


# Verifies that the status comes every 50 ms of simulated time, that the hand
# holds its fingers closed as the model left them, and that a command of
# Drake's sender opens them to the separation Drake's receiver reads, at rest,
# and closes them again.
def test_drakes_sender_and_receiver_open_and_close_the_hand(hand, tap):
    assert tap.wait(lambda: len(tap.statuses) >= 5), hand.log()
    steps = np.diff([m.utime for m in tap.statuses])
    assert np.all(steps % PERIOD_US == 0) and np.all(steps > 0), steps
    assert abs(tap.statuses[-1].actual_position_mm) < 1e3 * SETTLED
    pub = lcm.LCM(hand.url)
    for separation in (0.06, 0.02):
        pub.publish("SCHUNK_WSG_COMMAND", sender_command(separation, 15.0, 1.0).encode())
        settled = lambda: abs(received(tap.statuses[-1])[0][0] - separation) < SETTLED  # noqa: E731
        assert tap.wait(settled, timeout=10), (separation, tap.statuses[-1].actual_position_mm, hand.log())
        state, _ = received(tap.statuses[-1])
        assert abs(state[1]) < 1e-3, state


# Verifies that a command Drake's driver would not serve is refused with the
# reason (a reply named by the channel and its utime) and leaves the fingers
# where they were.
def test_bad_commands_are_refused(hand, tap):
    assert tap.wait(lambda: tap.statuses), hand.log()
    pub = lcm.LCM(hand.url)
    for utime, position_mm, force, says in [(201, 50.0, -1.0, "force is -1 N"),
                                             (202, 95.0, 10.0, "outside the fingers' range [0, 80] mm"),
                                             (203, float("nan"), 10.0, "target_position_mm is nan")]:
        m = lcmt_schunk_wsg_command()
        m.utime, m.target_position_mm, m.force = utime, position_mm, force
        pub.publish("SCHUNK_WSG_COMMAND", m.encode())
        r = tap.reply_to(utime, hand)
        assert r.client_id == "SCHUNK_WSG_COMMAND"
        assert r.code == contactsim.reply_t.INVALID_ARGUMENT
        assert says in r.message, r.message
    n = len(tap.statuses)
    assert tap.wait(lambda: len(tap.statuses) > n + 3), hand.log()
    assert abs(tap.statuses[-1].actual_position_mm) < 1e3 * SETTLED
