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
from pydrake.lcm import DrakeLcm  # noqa: E402
from pydrake.manipulation import SchunkWsgCommandSender, SchunkWsgStatusReceiver  # noqa: E402
from pydrake.systems.analysis import Simulator  # noqa: E402
from pydrake.systems.framework import DiagramBuilder  # noqa: E402
from pydrake.systems.lcm import LcmInterfaceSystem, LcmPublisherSystem, LcmSubscriberSystem  # noqa: E402
from pydrake.systems.primitives import ConstantVectorSource  # noqa: E402

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


def run_drake_wsg(url, separation, force, seconds):
    """Runs a Drake diagram for `seconds` of real time: SchunkWsgCommandSender
    publishing (separation m, force N) at 20 Hz, and LCM statuses read by
    SchunkWsgStatusReceiver; returns its last (separation m, its rate m/s)
    and force N."""
    lcm_ = DrakeLcm(url)
    b = DiagramBuilder()
    b.AddSystem(LcmInterfaceSystem(lcm_))
    sub = b.AddSystem(LcmSubscriberSystem.Make("SCHUNK_WSG_STATUS", lcmt_schunk_wsg_status, lcm_,
                                               use_cpp_serializer=True))
    receiver = b.AddSystem(SchunkWsgStatusReceiver())
    b.Connect(sub.get_output_port(), receiver.get_input_port(0))
    sender = b.AddSystem(SchunkWsgCommandSender())
    b.Connect(b.AddSystem(ConstantVectorSource([separation])).get_output_port(), sender.get_position_input_port())
    b.Connect(b.AddSystem(ConstantVectorSource([force])).get_output_port(), sender.get_force_limit_input_port())
    pub = b.AddSystem(LcmPublisherSystem.Make("SCHUNK_WSG_COMMAND", lcmt_schunk_wsg_command, lcm_,
                                              publish_period=0.05, use_cpp_serializer=True))
    b.Connect(sender.get_output_port(0), pub.get_input_port())
    diagram = b.Build()
    simulator = Simulator(diagram)
    simulator.set_target_realtime_rate(1.0)
    simulator.AdvanceTo(seconds)
    context = receiver.GetMyContextFromRoot(simulator.get_context())
    return receiver.get_state_output_port().Eval(context), receiver.get_force_output_port().Eval(context)[0]


# Verifies that the status comes every 50 ms of simulated time, that the hand
# holds its fingers closed as the model left them, and that Drake's
# SchunkWsgCommandSender opens them to the separation Drake's
# SchunkWsgStatusReceiver reads, at rest, and closes them again.
def test_drakes_sender_and_receiver_open_and_close_the_hand(hand, tap):
    assert tap.wait(lambda: len(tap.statuses) >= 5), hand.log()
    steps = np.diff([m.utime for m in tap.statuses])
    assert np.all(steps % PERIOD_US == 0) and np.all(steps > 0), steps
    assert abs(tap.statuses[-1].actual_position_mm) < 1e3 * SETTLED
    for separation in (0.06, 0.02):
        state, force = run_drake_wsg(hand.url, separation, 15.0, 1.5)
        assert abs(state[0] - separation) < SETTLED, (separation, state, hand.log())
        assert abs(state[1]) < 1e-3, state
        assert 0 <= force < 15.0, force


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
