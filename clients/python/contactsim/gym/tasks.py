"""Tasks for ContactsimEnv: what the world is, what is observed, what an
action pushes, and what is rewarded. Plain picklable objects, so that a
fleet worker on another node can build the same world."""
import numpy as np

G = 9.81


class HoverTask:
    """Hold a 2 kg box at ``target`` m above the ground
    (clients/python/examples/pd_hover.py as an environment). Action in
    [-1, 1]^6: force (x, y, z) times ``max_force`` N and torque times
    ``max_torque`` N m on the box, on top of m g upwards, so that zero
    action hovers wherever the box is. Reward: minus the height error (m)
    squared, minus a small action cost."""

    observed = ("box",)
    actuated = ("box",)

    def __init__(self, target=0.5, mass=2.0, half=0.1, start=0.1, max_force=20.0, max_torque=0.5, max_steps=240):
        self.target, self.mass, self.half, self.start = target, mass, half, start
        self.max_force, self.max_torque, self.max_steps = max_force, max_torque, max_steps

    def build(self, client):
        """Makes the world on an empty, paused server; returns {name: body id}."""
        client.reset()
        client.add_plane((0, 0, 1), 0.0)
        box = client.add_box((self.half,) * 3, position=(0, 0, self.start + self.half), mass=self.mass, name="box")
        return {"box": box}

    def forces(self, ids, action):
        a = np.clip(np.asarray(action, dtype=np.float64).reshape(-1, 6), -1.0, 1.0)[0]
        force = a[:3] * self.max_force + (0.0, 0.0, self.mass * G)
        return {ids["box"]: (force, a[3:] * self.max_torque)}

    def reward(self, state, ids, action):
        z = state.bodies[ids["box"]].position[2]
        return -float((z - self.target) ** 2) - 1e-3 * float(np.sum(np.square(action)))

    def terminated(self, state, ids):
        # flew off: nothing left to learn in this episode
        return bool(abs(state.bodies[ids["box"]].position[2] - self.target) > 5.0)
