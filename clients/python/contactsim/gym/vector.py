"""ContactsimEnv on a fleet: one environment per worker, stepped in
parallel; each worker's server is its own world (contactsim/fleet)."""
import gymnasium
import numpy as np
from gymnasium.vector.utils import batch_space


class FleetVectorEnv(gymnasium.vector.VectorEnv):
    """``num_envs`` copies of ``task`` on the first workers of ``fleet``
    (None: a local fleet of num_envs workers, closed with this). An
    episode that ends is reset in the same call (its last observation in
    ``infos["final_obs"]``)."""

    def __init__(self, task, num_envs=2, fleet=None, frame_skip=1):
        import ray
        from ..fleet import Fleet
        self._ray = ray
        self._own_fleet = fleet is None
        self.fleet = fleet or Fleet(workers=num_envs, progress=False)
        if len(self.fleet.workers) < num_envs:
            raise ValueError("the fleet has %d workers, fewer than num_envs=%d" % (len(self.fleet.workers), num_envs))
        self.workers = self.fleet.workers[:num_envs]
        ray.get([w.env_make.remote(task, frame_skip) for w in self.workers])
        self.num_envs = num_envs
        self.single_observation_space = task.observation_space()
        self.single_action_space = task.action_space()
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.action_space = batch_space(self.single_action_space, num_envs)

    def reset(self, *, seed=None, options=None):
        seeds = [None if seed is None else seed + i for i in range(self.num_envs)]
        out = self._ray.get([w.env_reset.remote(s) for w, s in zip(self.workers, seeds)])
        return np.stack([o for o, _ in out]), {"step": np.array([i["step"] for _, i in out])}

    def step(self, actions):
        out = self._ray.get([w.env_step.remote(a) for w, a in zip(self.workers, np.asarray(actions))])
        obs = np.stack([o[0] for o in out])
        rewards = np.array([o[1] for o in out], dtype=np.float64)
        terminated = np.array([o[2] for o in out])
        truncated = np.array([o[3] for o in out])
        infos = {"step": np.array([o[4]["step"] for o in out])}
        done = np.flatnonzero(terminated | truncated)
        if len(done):
            infos["final_obs"] = {int(i): obs[i].copy() for i in done}
            for i, (o, _) in zip(done, self._ray.get([self.workers[i].env_reset.remote() for i in done])):
                obs[i] = o
        return obs, rewards, terminated, truncated, infos

    def close(self, **kwargs):
        if self._own_fleet:
            self.fleet.close()
