"""What a job measures while the server steps, from the STATE and
CONTACTS messages the client receives (every step, fleet/server.py)."""
import threading

import numpy as np


class Collector:
    """Subscribes to the client while in a ``with`` block: max penetration,
    contacts per message, and the positions of ``follow`` ({name: id}) per STATE."""

    def __init__(self, client, follow=None, want_contacts=True):
        self.client = client
        self.follow = dict(follow or {})
        self.want_contacts = want_contacts
        self.max_depth = 0.0
        self.contact_counts = []
        self.last_contacts_step = -1
        self.steps = []
        self.positions = {name: [] for name in self.follow}
        self._cond = threading.Condition()
        self._removers = []

    def _on_state(self, state):
        self.steps.append(state.step)
        for name, body in self.follow.items():
            b = state.bodies.get(body)
            self.positions[name].append(b.position if b is not None else np.full(3, np.nan))

    def _on_contacts(self, contacts):
        depth = max((c.depth for c in contacts), default=0.0)
        with self._cond:
            self.max_depth = max(self.max_depth, depth)
            self.contact_counts.append(len(contacts))
            self.last_contacts_step = contacts.step
            self._cond.notify_all()

    def wait_contacts(self, step, timeout=1.0):
        """CONTACTS of the last step may trail its STATE: wait a little for it."""
        with self._cond:
            self._cond.wait_for(lambda: self.last_contacts_step >= step, timeout)

    def __enter__(self):
        if self.follow:
            self._removers.append(self.client.on_state(self._on_state))
        if self.want_contacts:
            self._removers.append(self.client.on_contacts(self._on_contacts))
        return self

    def __exit__(self, *exc):
        for remove in self._removers:
            remove()
        self._removers = []

    def trajectories(self):
        """{name: array (states, 3)} of the followed bodies' positions (m)."""
        return {name: np.array(p).reshape(-1, 3) for name, p in self.positions.items()}

    def mean_contacts(self):
        return float(np.mean(self.contact_counts)) if self.contact_counts else 0.0
