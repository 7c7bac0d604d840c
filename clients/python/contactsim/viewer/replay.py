"""The replay source of the viewer: an lcm-logger log read with
contactsim.logread, no server needed. The page asks for STATE number i
(a timeline slider, or its player at any speed) and gets the same frames as
live. A log holds no shapes: give a snapshot file of the run (--snapshot) to
draw them, else every body is a marker."""
import numpy as np

from ..logread import read_log
from .catalog import read_catalog
from .frames import contacts_frame, poses_frame
from .meshes import MeshFiles


class ReplaySource:
    mode = "replay"

    def __init__(self, log_path, snapshot_path=None, prefix=None):
        self.log = read_log(log_path, prefix=prefix)
        self.catalog = read_catalog(snapshot_path) if snapshot_path else {"bodies": [], "joints": []}
        self.meshes = MeshFiles()
        self.meshes.add_urls(self.catalog)
        self.catalog_version = 1
        c = self.log.contacts
        # contact points are stored in message order: message m owns points [start[m], start[m + 1])
        self._contact_start = np.searchsorted(c.frame, np.arange(len(c.step) + 1))

    def close(self):
        pass

    def hello(self):
        log = self.log
        return {"type": "hello", "mode": "replay", "log": log.path, "frames": len(log.step),
                "steps": log.step.tolist(), "times": log.time.tolist(),
                "kinetic": log.kinetic_energy.tolist(), "potential": log.potential_energy.tolist()}

    def poses(self, i):
        """The POSES frame of STATE number i (bodies that existed then)."""
        log = self.log
        pos, rot = log.position[i], log.orientation[i]
        present = ~np.isnan(pos[:, 0])
        return poses_frame(log.step[i], log.time[i], log.kinetic_energy[i], log.potential_energy[i],
                           log.body_ids[present], pos[present], rot[present])

    def status(self, i):
        """The panel's fields of the last STATUS at or before STATE i's step, or None."""
        ss = self.log.status
        m = int(np.searchsorted(ss.step, self.log.step[i], side="right")) - 1
        if m < 0:
            return None
        return {"type": "status", "paused": None, "mode": ss.mode[m], "method": ss.method[m], "method_params": "",
                "method_contract": "",
                "time": float(ss.time[m]), "step": int(ss.step[m]), "dt": float(ss.dt[m]),
                "step_rate": float(ss.step_rate[m]), "real_time_factor": float(ss.real_time_factor[m]),
                "num_bodies": int(ss.num_bodies[m]), "num_contacts": int(ss.num_contacts[m]),
                "max_penetration": float(ss.max_penetration[m]), "last_error": "", "version": ""}

    def contacts(self, i):
        """The CONTACTS frame of the last CONTACTS at or before STATE i's step."""
        c = self.log.contacts
        m = int(np.searchsorted(c.step, self.log.step[i], side="right")) - 1
        if m < 0:
            return contacts_frame(self.log.step[i], np.zeros((0, 3)), np.zeros((0, 3)))
        a, b = self._contact_start[m], self._contact_start[m + 1]
        return contacts_frame(c.step[m], c.point[a:b], c.normal[a:b])
