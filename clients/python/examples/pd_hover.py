#!/usr/bin/env python3
"""Holds a 2 kg box at a target height with a PD controller, in lockstep.

Every server step waits for this process's input, computed from the STATE of
the step before:

    F_z = m g + kp (z* - z) - kd v_z,   kp = m w^2, kd = 2 m w  (critical damping)

With w = 2 pi 1.5 rad/s the error falls as (1 + w t) e^(-w t): from 0.4 m to
below 1 cm in about 0.6 s. Exits 0 when the box ends within 1 cm of the target.

    python pd_hover.py [--lcm-url URL] [--prefix P] [--seconds S] [--target Z]
"""
import argparse
import math
import sys

import contactsim

MASS = 2.0                  # kg
HALF = 0.1                  # m
G = 9.81                    # m/s^2
OMEGA = 2 * math.pi * 1.5   # rad/s
KP = MASS * OMEGA ** 2      # N/m
KD = 2 * MASS * OMEGA       # N s/m
DT = 1.0 / 240


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--lcm-url", default=None)
    p.add_argument("--prefix", default="CONTACTSIM")
    p.add_argument("--seconds", type=float, default=3.0)
    p.add_argument("--target", type=float, default=0.5)
    a = p.parse_args()

    with contactsim.Client(url=a.lcm_url, prefix=a.prefix, timeout=5.0) as c:
        c.wait_for_server(timeout=10.0)
        c.pause()
        c.reset()
        c.add_plane((0, 0, 1), 0.0)
        box = c.add_box((HALF, HALF, HALF), position=(0, 0, HALF), mass=MASS)

        def pd(state):
            b = state.bodies[box]
            z, vz = b.position[2], b.linear_velocity[2]
            if state.step % 120 == 0:
                print("t %6.3f s  z %.4f m  v %+.4f m/s" % (state.time, z, vz), flush=True)
            return {box: (0.0, 0.0, MASS * G + KP * (a.target - z) - KD * vz)}

        steps = round(a.seconds / DT)
        with contactsim.Controller(c, pd, late="wait") as ctl:
            c.set_mode("lockstep")
            # step(n), not resume() then pause(): the run ends at step n exactly
            c.step(steps)
        z = c.state().bodies[box].position[2]
        print("final: step %d  z %.4f m  target %.4f m  error %.2e m" % (c.state().step, z, a.target, z - a.target))
        return 0 if abs(z - a.target) < 0.01 else 1


if __name__ == "__main__":
    sys.exit(main())
