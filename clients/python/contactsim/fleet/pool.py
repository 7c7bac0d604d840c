"""Fleet: Ray actors that each own a contactsim-server (fleet/worker.py),
and ``map``, which runs jobs on them and returns a pandas DataFrame.

Retries are ours rather than Ray's task retries, so a row can say what
happened: an actor that dies (Ray restarts it, max_restarts) or a server
that dies under a job gives that job back to the queue, preferably for
another worker, up to ``retries`` times; ``attempts`` and ``retried_after``
in its row tell. A job that fails for its own reasons (a refused command,
an unknown body) is not retried: its row carries the error.
"""
import collections
import os

import contactsim

from .worker import Worker


def _ray():
    try:
        import ray
    except ImportError as e:  # an optional dependency: say which
        raise ImportError("contactsim.fleet needs ray (pip install 'contactsim[fleet]' or make deps)") from e
    return ray


def _local_env():
    # Ray's local workers start from the driver's interpreter; these make
    # them find the same package and the same server build
    package_parent = os.path.dirname(os.path.abspath(contactsim.__path__[0]))
    env = {"PYTHONPATH": os.pathsep.join(p for p in (package_parent, os.environ.get("PYTHONPATH")) if p)}
    from ._paths import build_dir
    env["CONTACTSIM_BUILD_DIR"] = str(build_dir())
    if os.environ.get("CONTACTSIM_SERVER"):
        env["CONTACTSIM_SERVER"] = os.environ["CONTACTSIM_SERVER"]
    return env


class Fleet:
    """``Fleet(workers=N)``: a local Ray with N CPUs and N workers.
    ``Fleet(address="ray://head:10001" or "auto")``: a Ray cluster, one
    worker per CPU unless ``workers`` says. Use as a context manager, or
    call ``close()``."""

    def __init__(self, workers=None, address=None, retries=2, progress=True):
        ray = _ray()
        self._owns_ray = not ray.is_initialized()
        if self._owns_ray:
            if address:
                ray.init(address=address, log_to_driver=False)
            else:
                ray.init(num_cpus=workers or os.cpu_count(), include_dashboard=False, log_to_driver=False,
                         runtime_env={"env_vars": _local_env()})
        n = workers or max(1, int(ray.cluster_resources().get("CPU", 1)))
        free = ray.available_resources().get("CPU", 0)
        if not address and free < n:
            # each worker takes a CPU: the actors would wait for ever
            raise RuntimeError("this process's Ray has %g free CPUs and %d workers need one each "
                               "(another Fleet holds them? pass that fleet instead)" % (free, n))
        # restarted without end: a dead actor comes back with a new server
        actor = ray.remote(num_cpus=1, max_restarts=-1, max_task_retries=0)(Worker)
        self.workers = [actor.remote("w%d" % i) for i in range(n)]
        self.retries = int(retries)
        self.progress = progress

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def where(self):
        """[(host, actor pid, server pid)] per worker, starting their servers."""
        ray = _ray()
        return ray.get([w.where.remote() for w in self.workers])

    def map(self, jobs, progress=None):
        """Runs every job on the fleet; one row per job, in the order given."""
        from .table import rows_frame
        jobs = [j.packed() for j in jobs]
        rows = _Dispatch(_ray(), self.workers, jobs, self.retries).run(
            self.progress if progress is None else progress)
        return rows_frame(rows)

    def close(self):
        ray = _ray()
        if not ray.is_initialized():
            return
        try:
            ray.get([w.shutdown.remote() for w in self.workers], timeout=30)
        except Exception:  # noqa: BLE001 - a dead worker has nothing to shut down
            pass
        for w in self.workers:
            ray.kill(w, no_restart=True)
        self.workers = []
        if self._owns_ray:
            ray.shutdown()


class _Dispatch:
    """One job per idle worker until every job has its row."""

    def __init__(self, ray, workers, jobs, retries):
        self.ray, self.jobs, self.retries = ray, jobs, retries
        self.idle = list(workers)
        self.pending = collections.deque(range(len(jobs)))
        self.running = {}                        # ref -> (job index, worker)
        self.rows = [None] * len(jobs)
        self.attempts = [0] * len(jobs)
        self.notes = [[] for _ in jobs]          # why earlier attempts failed
        self.avoid = [None] * len(jobs)          # the worker a retry should not go back to

    def _pick(self, i):
        for k, w in enumerate(self.idle):
            if w is not self.avoid[i]:
                return self.idle.pop(k)
        return self.idle.pop(0)

    def _submit(self):
        while self.pending and self.idle:
            i = self.pending.popleft()
            w = self._pick(i)
            self.attempts[i] += 1
            self.running[w.run.remote(self.jobs[i])] = (i, w)

    def _row(self, ref, i):
        try:
            return self.ray.get(ref)
        except self.ray.exceptions.RayActorError as e:
            first = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
            return dict(self.jobs[i].describe(), error="worker died: %s" % first[:200], retryable=True)

    def run(self, progress):
        from tqdm.auto import tqdm
        with tqdm(total=len(self.jobs), unit="job", desc="fleet", disable=not progress) as bar:
            while self.pending or self.running:
                self._submit()
                done, rest = self.ray.wait(list(self.running), num_returns=1)
                if rest:   # on a large fleet several finish at once: one pass for them all
                    done += self.ray.wait(rest, num_returns=len(rest), timeout=0)[0]
                for ref in done:
                    i, w = self.running.pop(ref)
                    self.idle.append(w)      # a dead actor is being restarted by Ray
                    row = self._row(ref, i)
                    if row.get("retryable") and self.attempts[i] <= self.retries:
                        self.notes[i].append(row["error"])
                        self.avoid[i] = w
                        self.pending.appendleft(i)
                        continue
                    row.update(attempts=self.attempts[i], retried_after="; ".join(self.notes[i]))
                    self.rows[i] = row
                    bar.update(1)
        return self.rows


def run_sequential(jobs, progress=False):
    """The same jobs one after another on one local server, without Ray:
    the reference a fleet's hashes are checked against."""
    from tqdm.auto import tqdm

    from .table import rows_frame
    worker = Worker("sequential")
    try:
        rows = [dict(worker.run(j.packed()), attempts=1, retried_after="")
                for j in tqdm(jobs, unit="job", desc="sequential", disable=not progress)]
    finally:
        worker.shutdown()
    return rows_frame(rows)
