"""Moves contactsim's simulated KUKA iiwa with Drake's own driver systems.

Two commands, from the repository's root:

    build/bin/contactsim-server --config config/iiwa_driver.pbtxt
    .venv/bin/python examples/iiwa_drake_controller.py

The controller is a Drake diagram as it would drive a real iiwa: an
IiwaStatusReceiver reads lcmt_iiwa_status from IIWA_STATUS, an
IiwaCommandSender writes lcmt_iiwa_command to IIWA_COMMAND every 5 ms. It
waits for the arm's first status, then sweeps each joint through a slow sine
about the pose it found (or holds --pose) and prints the tracking error once
a second. docs/actuators.md, "Drake's arm driver", says what each field of
the status holds.

--report prints the receiver's last outputs as one JSON line at the end
(tests/python/test_iiwa_driver.py reads it).
"""
import argparse
import json
import math
import sys

import numpy as np
from pydrake.lcm import DrakeLcm
from pydrake.manipulation import IiwaCommandSender, IiwaStatusReceiver
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.lcm import LcmInterfaceSystem, LcmPublisherSystem, LcmSubscriberSystem
from pydrake.systems.primitives import ConstantVectorSource

from drake import lcmt_iiwa_command, lcmt_iiwa_status

JOINTS = 7
COMMAND_PERIOD = 0.005  # s: Drake's iiwa driver runs at 200 Hz


class Sweep(LeafSystem):
    """q(t) = q0 + amplitude sin(2 pi t / period), phase-shifted per joint;
    q0 is the pose the arm stood in when the controller started."""

    def __init__(self, q0, amplitude, period):
        super().__init__()
        self.q0 = np.asarray(q0)
        self.amplitude, self.period = amplitude, period
        self.DeclareVectorOutputPort("position", JOINTS, self._calc)

    def _calc(self, context, out):
        t = context.get_time()
        phase = 2 * math.pi * t / self.period + np.arange(JOINTS) * 0.5
        out.SetFromVector(self.q0 + self.amplitude * np.sin(phase) * min(1.0, t))


def first_status(lcm, channel, timeout):
    """The first lcmt_iiwa_status on `channel`, or None after `timeout` s."""
    got = []
    lcm.Subscribe(channel, lambda data: got.append(lcmt_iiwa_status.decode(data)))
    waited = 0
    while not got and waited < timeout * 1000:
        waited += 50
        lcm.HandleSubscriptions(50)
    return got[0] if got else None


def build(lcm, args, q0):
    b = DiagramBuilder()
    b.AddSystem(LcmInterfaceSystem(lcm))
    status_sub = b.AddSystem(LcmSubscriberSystem.Make(args.status_channel, lcmt_iiwa_status, lcm,
                                                      use_cpp_serializer=True))
    receiver = b.AddSystem(IiwaStatusReceiver(JOINTS))
    b.Connect(status_sub.get_output_port(), receiver.get_input_port())
    sender = b.AddSystem(IiwaCommandSender(JOINTS))
    command_pub = b.AddSystem(LcmPublisherSystem.Make(args.command_channel, lcmt_iiwa_command, lcm,
                                                      publish_period=COMMAND_PERIOD, use_cpp_serializer=True))
    b.Connect(sender.get_output_port(), command_pub.get_input_port())
    if args.pose is not None:
        target = b.AddSystem(ConstantVectorSource(np.asarray(args.pose)))
    else:
        target = b.AddSystem(Sweep(q0, args.amplitude, args.period))
    b.Connect(target.get_output_port(), sender.get_position_input_port())
    torque = b.AddSystem(ConstantVectorSource(np.asarray(args.torque or [0.0] * JOINTS)))
    b.Connect(torque.get_output_port(), sender.get_torque_input_port())
    return b.Build(), receiver, target


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--lcm-url", default="", help="LCM URL (default: $LCM_DEFAULT_URL, else LCM's)")
    p.add_argument("--command-channel", default="IIWA_COMMAND")
    p.add_argument("--status-channel", default="IIWA_STATUS")
    p.add_argument("--seconds", type=float, default=20.0, help="how long to run (s of wall-clock time)")
    p.add_argument("--pose", type=float, nargs=JOINTS, help="hold these joint angles (rad) instead of sweeping")
    p.add_argument("--torque", type=float, nargs=JOINTS, help="feed-forward torques (N m), default zeros")
    p.add_argument("--amplitude", type=float, default=0.3, help="sweep amplitude (rad)")
    p.add_argument("--period", type=float, default=4.0, help="sweep period (s)")
    p.add_argument("--report", action="store_true", help="print the receiver's last outputs as JSON")
    args = p.parse_args()

    lcm = DrakeLcm(args.lcm_url) if args.lcm_url else DrakeLcm()
    status = first_status(lcm, args.status_channel, timeout=10.0)
    if status is None:
        sys.exit("no lcmt_iiwa_status on %s within 10 s: is contactsim-server running with "
                 "config/iiwa_driver.pbtxt?" % args.status_channel)
    q0 = list(status.joint_position_measured)
    diagram, receiver, target = build(lcm, args, q0)
    simulator = Simulator(diagram)
    simulator.set_target_realtime_rate(1.0)
    context = simulator.get_mutable_context()
    simulator.Initialize()
    t = 0.0
    while t < args.seconds:
        t = min(args.seconds, t + 1.0)
        simulator.AdvanceTo(t)
        rc = receiver.GetMyContextFromRoot(context)
        q = receiver.get_position_measured_output_port().Eval(rc)
        q_cmd = receiver.get_position_commanded_output_port().Eval(rc)
        if not args.report:
            print("t = %5.1f s  |q_commanded - q_measured| max %.2e rad" % (t, np.max(np.abs(q_cmd - q))))
    if args.report:
        rc = receiver.GetMyContextFromRoot(context)
        out = {name: list(getattr(receiver, "get_%s_output_port" % name)().Eval(rc))
               for name in ("position_commanded", "position_measured", "velocity_estimated",
                            "torque_commanded", "torque_measured", "torque_external")}
        out["time_measured"] = float(receiver.get_time_measured_output_port().Eval(rc)[0])
        out["start_position"] = q0
        print(json.dumps(out))


if __name__ == "__main__":
    main()
