"""Moves contactsim's simulated KUKA iiwa or Franka Panda with Drake's own driver systems.

Two commands, from the repository's root:

    build/bin/contactsim-server --config config/iiwa_driver.pbtxt     # or config/panda_driver.pbtxt
    .venv/bin/python examples/drake_arm_controller.py                 # --arm panda for the Panda

The controller is a Drake diagram as it would drive the real arm: a status
receiver (IiwaStatusReceiver, PandaStatusReceiver) reads the driver's status
(lcmt_iiwa_status on IIWA_STATUS, lcmt_panda_status on PANDA_STATUS), a
command sender (IiwaCommandSender, PandaCommandSender in position and torque
mode) writes its commands every 5 ms. It waits for the arm's first status,
then sweeps each joint through a slow sine about the pose it found (or holds
--pose) and prints the tracking error once a second. docs/actuators.md,
"Drake's arm driver", says what each field of the status holds.

--report prints the receiver's last outputs as one JSON line at the end
(tests/python/test_iiwa_driver.py and test_panda_driver.py read it).
"""
import argparse
import json
import math
import sys

import numpy as np
from pydrake.lcm import DrakeLcm
from pydrake.manipulation import (IiwaCommandSender, IiwaStatusReceiver, PandaCommandSender, PandaControlMode,
                                  PandaStatusReceiver)
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder, LeafSystem
from pydrake.systems.lcm import LcmInterfaceSystem, LcmPublisherSystem, LcmSubscriberSystem
from pydrake.systems.primitives import ConstantVectorSource

from drake import lcmt_iiwa_command, lcmt_iiwa_status, lcmt_panda_command, lcmt_panda_status

JOINTS = 7
COMMAND_PERIOD = 0.005  # s: the iiwa driver's 200 Hz; the Panda's drives hold the last command between two


class Arm:
    """What differs between Drake's iiwa and Panda driver systems: the
    messages, the channels' prefix, the systems and their outputs."""

    def __init__(self, prefix, command, status, sender, receiver, measured_field, outputs):
        self.prefix, self.command, self.status = prefix, command, status
        self.sender, self.receiver = sender, receiver
        self.measured_field = measured_field  # the status field of the measured joint angles
        self.outputs = outputs                # the receiver's output ports --report prints


ARMS = {
    "iiwa": Arm("IIWA", lcmt_iiwa_command, lcmt_iiwa_status, lambda: IiwaCommandSender(JOINTS),
                lambda: IiwaStatusReceiver(JOINTS), "joint_position_measured",
                ("position_commanded", "position_measured", "velocity_estimated", "torque_commanded",
                 "torque_measured", "torque_external", "time_measured")),
    "panda": Arm("PANDA", lcmt_panda_command, lcmt_panda_status,
                 lambda: PandaCommandSender(JOINTS, PandaControlMode.kPosition | PandaControlMode.kTorque),
                 lambda: PandaStatusReceiver(JOINTS), "joint_position",
                 ("position_commanded", "position_measured", "velocity_commanded", "velocity_measured",
                  "torque_commanded", "torque_measured", "torque_external")),
}


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


def first_status(lcm, arm, channel, timeout):
    """The first status of `arm` on `channel`, or None after `timeout` s."""
    got = []
    lcm.Subscribe(channel, lambda data: got.append(arm.status.decode(data)))
    waited = 0
    while not got and waited < timeout * 1000:
        waited += 50
        lcm.HandleSubscriptions(50)
    return got[0] if got else None


def build(lcm, arm, args, q0):
    b = DiagramBuilder()
    b.AddSystem(LcmInterfaceSystem(lcm))
    status_sub = b.AddSystem(LcmSubscriberSystem.Make(args.status_channel, arm.status, lcm, use_cpp_serializer=True))
    receiver = b.AddSystem(arm.receiver())
    b.Connect(status_sub.get_output_port(), receiver.get_input_port())
    sender = b.AddSystem(arm.sender())
    command_pub = b.AddSystem(LcmPublisherSystem.Make(args.command_channel, arm.command, lcm,
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
    p.add_argument("--arm", choices=sorted(ARMS), default="iiwa", help="the driver protocol (default: iiwa)")
    p.add_argument("--lcm-url", default="", help="LCM URL (default: $LCM_DEFAULT_URL, else LCM's)")
    p.add_argument("--command-channel", help="default: Drake's, IIWA_COMMAND or PANDA_COMMAND")
    p.add_argument("--status-channel", help="default: Drake's, IIWA_STATUS or PANDA_STATUS")
    p.add_argument("--seconds", type=float, default=20.0, help="how long to run (s of wall-clock time)")
    p.add_argument("--pose", type=float, nargs=JOINTS, help="hold these joint angles (rad) instead of sweeping")
    p.add_argument("--torque", type=float, nargs=JOINTS, help="feed-forward torques (N m), default zeros")
    p.add_argument("--amplitude", type=float, default=0.3, help="sweep amplitude (rad)")
    p.add_argument("--period", type=float, default=4.0, help="sweep period (s)")
    p.add_argument("--report", action="store_true", help="print the receiver's last outputs as JSON")
    args = p.parse_args()
    arm = ARMS[args.arm]
    args.command_channel = args.command_channel or arm.prefix + "_COMMAND"
    args.status_channel = args.status_channel or arm.prefix + "_STATUS"

    lcm = DrakeLcm(args.lcm_url) if args.lcm_url else DrakeLcm()
    status = first_status(lcm, arm, args.status_channel, timeout=10.0)
    if status is None:
        sys.exit("no %s on %s within 10 s: is contactsim-server running with config/%s_driver.pbtxt?"
                 % (arm.status.__name__, args.status_channel, args.arm))
    q0 = list(getattr(status, arm.measured_field))
    diagram, receiver, target = build(lcm, arm, args, q0)
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
        out = {name: list(getattr(receiver, "get_%s_output_port" % name)().Eval(rc)) for name in arm.outputs}
        if "time_measured" in out:
            out["time_measured"] = float(out["time_measured"][0])
        out["start_position"] = q0
        print(json.dumps(out))


if __name__ == "__main__":
    main()
