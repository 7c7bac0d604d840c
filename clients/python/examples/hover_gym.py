"""The PD hover task as a Gymnasium environment on a fleet of 2 workers,
driven by a random policy (docs/fleet.md, "Reinforcement learning").

    CONTACTSIM_BUILD_DIR=build .venv/bin/python clients/python/examples/hover_gym.py [--episodes 3]

Each worker owns its own contactsim-server in lockstep; an action is a
force and torque on the box on top of m g (contactsim.gym.HoverTask). A
PD policy (examples/pd_hover.py) would hold the box at 0.5 m; the random
one only shows the loop: reset, step, rewards, automatic resets.
"""
import argparse
import sys

import numpy as np

from contactsim.gym import FleetVectorEnv, HoverTask


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--episodes", type=int, default=3, help="episodes per worker")
    p.add_argument("--episode-steps", type=int, default=120)
    a = p.parse_args()

    venv = FleetVectorEnv(HoverTask(max_steps=a.episode_steps), num_envs=a.workers)
    try:
        rng = np.random.default_rng(0)
        obs, _ = venv.reset(seed=0)
        returns = np.zeros(a.workers)
        finished = []
        while len(finished) < a.episodes * a.workers:
            obs, rewards, terminated, truncated, infos = venv.step(rng.uniform(-1, 1, venv.action_space.shape))
            returns += rewards
            for i in np.flatnonzero(terminated | truncated):
                finished.append(returns[i])
                print("worker %d: episode return %.4f, box at z %.3f m" % (
                    i, returns[i], infos["final_obs"][int(i)][2]), flush=True)
                returns[i] = 0.0
        print("mean return of %d episodes: %.4f" % (len(finished), np.mean(finished)))
    finally:
        venv.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
