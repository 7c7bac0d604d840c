"""Joint trajectories of a log (read_log's ``joints``; docs/actuators.md,
"Joint channels"): one row per STATE, from its joint block, which every
STATE carries; JOINT_STATE messages, where the server published them, name
the joints (else a joint is named by its id in decimal)."""
from types import SimpleNamespace

import numpy as np

from . import joint_state_t


class JointTrajectories:
    """Collects the joint blocks of STATE messages and the names of
    JOINT_STATE messages, then stacks them into arrays."""

    def __init__(self):
        self._time, self._step, self._rows = [], [], []
        self._names, self._models = {}, {}

    def add_state(self, m):
        """A decoded state_t: a row, when it carries joints."""
        if m.num_joints == 0:
            return
        self._time.append(m.time)
        self._step.append(m.step)
        rows = {}
        for j, model, q, v, u in zip(m.joint_ids, m.joint_model_ids, m.joint_positions, m.joint_velocities,
                                     m.joint_efforts):
            rows[int(j)] = (q, v, u)
            self._names.setdefault(int(j), str(int(j)))
            self._models[int(j)] = int(model)
        self._rows.append(rows)

    def add(self, data):
        """An encoded JOINT_STATE: the joints' names."""
        m = joint_state_t.decode(data)
        for j, name in zip(m.joint_ids, m.names):
            self._names[int(j)] = name

    def result(self):
        """``time``, ``step`` (N,); ``joint_ids`` (J,) every joint seen, in
        first-seen order (grouped by model); ``joint_index`` id -> column;
        ``names`` and ``model_ids`` (J,); ``position``, ``velocity``,
        ``effort`` (N, J), NaN where a joint was absent."""
        ids = list(self._names)
        column = {j: i for i, j in enumerate(ids)}
        out = np.full((len(self._rows), len(ids), 3), np.nan)
        for n, rows in enumerate(self._rows):
            for j, values in rows.items():
                out[n, column[j]] = values
        return SimpleNamespace(
            time=np.asarray(self._time, dtype=np.float64), step=np.asarray(self._step, dtype=np.int64),
            joint_ids=np.asarray(ids, dtype=np.int64), joint_index=column,
            names=[self._names[j] for j in ids], model_ids=np.asarray([self._models[j] for j in ids], dtype=np.int64),
            position=out[:, :, 0], velocity=out[:, :, 1], effort=out[:, :, 2])
