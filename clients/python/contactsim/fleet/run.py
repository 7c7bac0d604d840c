"""Runs one job on one server: load the world, switch the method, step,
measure. The fleet's workers and a sequential run call the same function,
so their state hashes can be compared one for one."""
import threading
import time
from pathlib import Path

from ..viewer.catalog import read_catalog

# s without PROGRESS (sent every ~0.2 s) before a STEP is given up: a dead server shows soon
STEP_SILENCE_TIMEOUT = 10.0


def _hex(h):
    return "%016x" % (h & 0xFFFFFFFFFFFFFFFF)


class NextState:
    """The first STATE after the set-up commands (the server is paused, so
    it publishes one only after a command that changes the world)."""

    def __init__(self, client):
        self.state = None
        self._event = threading.Event()
        self._remove = client.on_state(self._on_state)

    def _on_state(self, state):
        self.state = state
        self._event.set()

    def wait(self, step, timeout):
        deadline = time.monotonic() + timeout
        while self.state is None or self.state.step != step:
            self._event.clear()
            if not self._event.wait(max(0.0, deadline - time.monotonic())):
                raise RuntimeError("no STATE of step %d after loading the world" % step)
        self._remove()
        return self.state


def load_world(client, job, workdir):
    """Loads the job's scene or snapshot and method; returns the first State."""
    first = NextState(client)
    client.pause()
    if job.scene is not None:
        path = Path(workdir) / "job-scene.pbtxt"
        path.write_text(job.scene)
        reply = client.load_scene(path, timeout=30.0)
    else:
        path = Path(workdir) / "job-snapshot.pb"
        path.write_bytes(job.snapshot)
        reply = client.restore(path=path)
    if job.method:
        reply = client.set_contact_method(job.method, **(job.params or {}))
    return first.wait(reply.step, client.timeout)


def body_ids(client, names, workdir):
    """{name: id} for the named bodies, from a snapshot's catalog (STATE has no names)."""
    path = Path(workdir) / "job-catalog.pb"
    client.snapshot(path=path)
    bodies = read_catalog(path)["bodies"]
    by_name = {b["name"]: b["id"] for b in bodies if b["name"]}
    by_name.update({b["id"]: b["id"] for b in bodies})   # ids may be given as they are
    missing = [str(n) for n in names if n not in by_name]
    if missing:
        raise KeyError("no body named %s in the world (names: %s)" % (
            ", ".join(missing), ", ".join(sorted(b["name"] for b in bodies if b["name"])) or "none"))
    return {n: by_name[n] for n in names}


def run_job(client, job, workdir):
    """The job's row: its description, final state hash and step, and the
    metrics and trajectories it asked for. Raises on a refused command."""
    from .collect import Collector  # numpy only; kept beside run_job's one use

    initial = load_world(client, job, workdir)
    follow = body_ids(client, job.bodies, workdir) if "trajectory" in job.collect else {}
    with Collector(client, follow, want_contacts="metrics" in job.collect) as col:
        t0 = time.perf_counter()
        reply = client.step(int(job.steps), timeout=STEP_SILENCE_TIMEOUT)
        wall = time.perf_counter() - t0
        if "metrics" in job.collect:
            col.wait_contacts(reply.step)
    final = client.state()
    row = dict(job.describe(), final_step=final.step, state_hash=_hex(final.state_hash))
    if "metrics" in job.collect:
        e0 = initial.kinetic_energy + initial.potential_energy
        e1 = final.kinetic_energy + final.potential_energy
        row.update(max_penetration=col.max_depth, mean_contacts=col.mean_contacts(),
                   energy_initial=e0, energy_final=e1, energy_drift=e1 - e0,
                   ms_per_step=1000.0 * wall / int(job.steps))
    if follow:
        row["trajectory"] = col.trajectories()
    return row
