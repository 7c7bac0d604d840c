#!/usr/bin/env python3
"""Drops a ball (restitution 0.5) from 1 m onto a plane and prints each bounce apex.

The ball's lowest point starts 1 m above the plane; with restitution 0.5 each
apex is a quarter of the one before: 0.25 m, 0.0625 m, ... The server is
paused and stepped one step at a time so that no apex is missed, and left
running afterwards if it was running before.

    python drop_ball.py [--lcm-url URL] [--prefix P] [--seconds S]
"""
import argparse

import contactsim

RADIUS = 0.1


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--lcm-url", default=None)
    p.add_argument("--prefix", default="CONTACTSIM")
    p.add_argument("--seconds", type=float, default=3.0, help="simulated time to run")
    a = p.parse_args()

    with contactsim.Client(url=a.lcm_url, prefix=a.prefix) as c:
        st = c.wait_for_server()
        print("server %s, method %s" % (st.version, st.method))
        c.pause()
        c.reset()
        c.add_plane((0, 0, 1), 0.0, restitution=0.5)
        ball = c.add_sphere(RADIUS, position=(0, 0, 1.0 + RADIUS), restitution=0.5)
        dt = c.step(1).time  # time after one step = dt
        heights, vz_prev, bounces = [], 0.0, 0
        for _ in range(int(a.seconds / dt)):
            c.step(1)
            b = c.state().bodies[ball]
            h, vz = b.position[2] - RADIUS, b.linear_velocity[2]
            heights.append(h)
            if vz_prev > 0 >= vz:  # rising -> falling: an apex
                bounces += 1
                print("bounce %d: apex %.4f m (ideal %.4f m)" % (bounces, max(heights[-3:]), 0.25 ** bounces))
            vz_prev = vz
        if not st.paused:
            c.resume()  # leave the server running, as it was


if __name__ == "__main__":
    main()
