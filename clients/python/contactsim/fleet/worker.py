"""A fleet worker: owns one contactsim-server and runs jobs on it, one at a
time. A plain class; fleet/pool.py makes it a Ray actor.

A job never raises out of ``run``: its row carries ``error`` instead, and
``retryable`` when the server died under it (the worker starts a new one
for the next job, and the fleet runs this job again, elsewhere if it can).
"""
import os
import socket
import traceback

from .run import run_job
from .server import OwnedServer


class Worker:
    def __init__(self, name=""):
        self.name = name or "worker"
        self.server = None
        self.env = None
        self.jobs_run = 0
        self.servers_started = 0

    def _ensure_server(self):
        """The running server; a new one when there is none or it died."""
        if self.server is None or not self.server.alive():
            if self.server is not None:
                self.server.stop()
            self.server = OwnedServer()
            self.servers_started += 1
        return self.server

    def where(self):
        """(host, actor pid, server pid): what a test or a log needs to find this worker."""
        return socket.gethostname(), os.getpid(), self._ensure_server().pid

    def run(self, job):
        self.jobs_run += 1
        where = {"worker": self.name, "host": socket.gethostname()}
        try:
            self._close_env()   # a job needs the server back from lockstep
            server = self._ensure_server()
            row = run_job(server.client, job, server.workdir)
            return dict(row, **where, error="", retryable=False)
        except Exception as e:  # noqa: BLE001 - the error goes into the job's row
            died = self.server is not None and not self.server.alive()
            why = "%s: %s" % (type(e).__name__, e)
            if died:
                why = "server died (exit %s) during the job; %s" % (self.server.proc.returncode, why)
            return dict(job.describe(), **where, error=why, retryable=died,
                        traceback=traceback.format_exc(limit=3))

    # gym environments on the fleet (contactsim/gym/vector.py)
    def env_make(self, task, frame_skip=1):
        from ..gym.env import ContactsimEnv
        self._close_env()
        self.env = ContactsimEnv(self._ensure_server().client, task, frame_skip=frame_skip)
        return True

    def _close_env(self):
        if self.env is not None:
            self.env.close()
            self.env = None

    def env_reset(self, seed=None):
        return self.env.reset(seed=seed)

    def env_step(self, action):
        return self.env.step(action)

    def shutdown(self):
        self._close_env()
        if self.server is not None:
            self.server.stop()
            self.server = None
        return True
