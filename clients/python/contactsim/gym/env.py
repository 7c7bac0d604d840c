"""A Gymnasium environment over lockstep (docs/lockstep.md, docs/fleet.md).

The environment is the server's one lockstep controller: each ``step``
sends the action's input (the task's forces on bodies and commands to
joints) for the next world step and waits for that step's STATE. ``reset`` restores the snapshot taken after the
task built its world, so every episode starts bit for bit the same.
"""
import gymnasium
import numpy as np

from ..errors import TimeoutError
from ..fleet.run import NextState

SLOT = "gym_reset"
RESEND_S = 0.5        # an input lost on UDP is sent again after this long
STEP_TIMEOUT_S = 30.0


class ContactsimEnv(gymnasium.Env):
    """``client``: a client of a server that this environment may take over
    (it resets the world); ``task``: e.g. contactsim.gym.HoverTask();
    ``frame_skip``: world steps per action."""

    metadata = {"render_modes": []}

    def __init__(self, client, task, frame_skip=1):
        self.client, self.task, self.frame_skip = client, task, int(frame_skip)
        client.pause()
        self.ids = task.build(client)
        client.snapshot(SLOT)
        client.register_controller(late="wait")
        client.set_mode("lockstep")
        self.observation_space = task.observation_space()
        self.action_space = task.action_space()
        self.state = None
        self.steps = 0

    def _obs(self, state):
        return self.task.observe(self.client, state, self.ids)

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.client.pause()
        first = NextState(self.client)
        reply = self.client.restore(SLOT)
        self.state = first.wait(reply.step, STEP_TIMEOUT_S)
        self.client.resume()          # lockstep: the server now waits for our input
        self.steps = 0
        return self._obs(self.state), {"step": self.state.step, "state_hash": self.state.state_hash}

    def _advance(self, forces, joints):
        target = self.state.step + 1
        _, payload = self.client._encode_input(target, forces, joints)
        for _ in range(int(STEP_TIMEOUT_S / RESEND_S)):
            self.client._publish_input(payload)   # the same request id: a duplicate is ignored
            try:
                return self.client.wait_for_state(lambda s: s.step == target, timeout=RESEND_S)
            except TimeoutError:
                continue
        raise TimeoutError("no STATE of step %d within %gs" % (target, STEP_TIMEOUT_S))

    def step(self, action):
        forces, joints = self.task.inputs(self.ids, action)
        for _ in range(self.frame_skip):
            self.state = self._advance(forces, joints)
        self.steps += 1
        obs = self._obs(self.state)
        reward = self.task.reward(self.state, self.ids, action)
        terminated = self.task.terminated(self.state, self.ids)
        truncated = self.steps >= self.task.max_steps
        return obs, reward, terminated, truncated, {"step": self.state.step, "state_hash": self.state.state_hash}

    def close(self):
        try:
            self.client.pause()
            self.client.release_controller()
            self.client.set_mode("free_run")   # the server may run jobs again
        except Exception:  # noqa: BLE001 - the server may be gone already
            pass
