"""Tasks for ContactsimEnv: what the world is, what is observed, what an
action does, and what is rewarded. Plain picklable objects, so that a
fleet worker on another node can build the same world.

A task has ``build(client) -> ids``, ``observation_space()``,
``action_space()``, ``observe(client, state, ids) -> array``,
``inputs(ids, action) -> (forces, JointCommand or None)`` (the lockstep
input of one step), ``reward``, ``terminated`` and ``max_steps``.
"""
import gymnasium
import numpy as np

from ..actuators import JointCommand

G = 9.81
BODY_DIMS = 13        # position 3, orientation (w, x, y, z) 4, linear 3 and angular 3 velocity


class HoverTask:
    """Hold a 2 kg box at ``target`` m above the ground
    (clients/python/examples/pd_hover.py as an environment). Action in
    [-1, 1]^6: force (x, y, z) times ``max_force`` N and torque times
    ``max_torque`` N m on the box, on top of m g upwards, so that zero
    action hovers wherever the box is. Observation: the box's position,
    orientation and velocities. Reward: minus the height error (m)
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

    def observation_space(self):
        return gymnasium.spaces.Box(-np.inf, np.inf, (BODY_DIMS * len(self.observed),), np.float64)

    def action_space(self):
        return gymnasium.spaces.Box(-1.0, 1.0, (6 * len(self.actuated),), np.float64)

    def observe(self, client, state, ids):
        parts = []
        for name in self.observed:
            b = state.bodies[ids[name]]
            parts += [b.position, b.orientation, b.linear_velocity, b.angular_velocity]
        return np.concatenate(parts)

    def forces(self, ids, action):
        a = np.clip(np.asarray(action, dtype=np.float64).reshape(-1, 6), -1.0, 1.0)[0]
        force = a[:3] * self.max_force + (0.0, 0.0, self.mass * G)
        return {ids["box"]: (force, a[3:] * self.max_torque)}

    def inputs(self, ids, action):
        return self.forces(ids, action), None

    def reward(self, state, ids, action):
        z = state.bodies[ids["box"]].position[2]
        return -float((z - self.target) ** 2) - 1e-3 * float(np.sum(np.square(action)))

    def terminated(self, state, ids):
        # flew off: nothing left to learn in this episode
        return bool(abs(state.bodies[ids["box"]].position[2] - self.target) > 5.0)


class ArmTask:
    """Drive a robot model's joints to ``goal`` (rad or m, one per joint
    with a coordinate). ``model``: a URDF or SDF path the server can read,
    loaded with its base fixed. ``control``: "torque" (action in [-1, 1]^n
    times ``max_effort``, the joints' effort for the step) or "position"
    (action in [-1, 1]^n times ``span`` rad, the joints' targets for the
    step, held by standing gains ``kp`` and ``kd``). Observation: the
    joints' positions and velocities (JOINT_STATE of the step). Reward:
    minus the squared distance to the goal."""

    def __init__(self, model, goal, control="torque", max_effort=50.0, span=np.pi, kp=300.0, kd=30.0,
                 max_steps=240):
        if control not in ("torque", "position"):
            raise ValueError("control must be 'torque' or 'position', got %r" % (control,))
        self.model, self.goal, self.control = model, np.asarray(goal, dtype=np.float64), control
        self.max_effort, self.span, self.kp, self.kd, self.max_steps = max_effort, span, kp, kd, max_steps

    def build(self, client):
        client.reset()
        arm = client.load_model(self.model, name="arm", fixed_base=True)
        if len(arm.actuated_joints) != len(self.goal):
            raise ValueError("the model has %d joints with a coordinate, the goal %d values"
                             % (len(arm.actuated_joints), len(self.goal)))
        if self.control == "position":
            arm.set_joint_targets(np.zeros(len(self.goal)), kp=self.kp, kd=self.kd)
        return {"model": arm.id, "joints": [arm.joint_id(n) for n in arm.actuated_joints]}

    def observation_space(self):
        return gymnasium.spaces.Box(-np.inf, np.inf, (2 * len(self.goal),), np.float64)

    def action_space(self):
        return gymnasium.spaces.Box(-1.0, 1.0, (len(self.goal),), np.float64)

    def observe(self, client, state, ids):
        js = client.joints_of(state)  # STATE carries the joints of its step
        q, v, _ = js.of_model(ids["model"])
        self._q = q  # the reward's, which sees only STATE
        return np.concatenate([q, v])

    def inputs(self, ids, action):
        a = np.clip(np.asarray(action, dtype=np.float64).reshape(-1), -1.0, 1.0)
        if self.control == "torque":
            return None, JointCommand(ids["joints"], torque=a * self.max_effort)
        return None, JointCommand(ids["joints"], target_position=a * self.span)

    def reward(self, state, ids, action):
        return -float(np.sum(np.square(self._q - self.goal)))

    def terminated(self, state, ids):
        return False
