"""One contactsim-server child process on a private LCM URL, and a Client to it.

A fleet worker owns one of these. The URL has a port of its own (the kernel
picks a free one) and ttl=0, so the server's multicast never leaves the
node: Ray, not LCM, carries jobs and results between machines. The server
runs free_run and paused, with STATE and CONTACTS every step so that a job
sees every step's state and penetration (config_overrides below).
"""
import ctypes
import signal
import socket
import subprocess
import tempfile
import uuid
from pathlib import Path

from ..client import Client
from ._paths import repo_root, server_binary
from ..errors import TimeoutError
from ..process import interrupt

START_TIMEOUT = 30.0   # a sanitizer build on a busy 2-core machine starts slowly
EXIT_TIMEOUT = 10.0
# every step published: jobs collect penetration and trajectories per step
# threads: each Ray worker owns one server and Ray gives each worker a core,
# so a server using every core would oversubscribe them
CONFIG_OVERRIDES = {"state_rate_hz": "0", "contacts_rate_hz": "0", "status_rate_hz": "1",
                    "log_level": '"warn"', "threads": "1"}


def private_url():
    """A host-only URL on a UDP port that is free right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("", 0))
        port = s.getsockname()[1]
    return "udpm://239.255.76.67:%d?ttl=0&recv_buf_size=8388608" % port


def _write_config(folder):
    # the repository's config with our rates: publishing settings only, no physics
    base = repo_root() / "config" / "server.pbtxt"
    lines = base.read_text().splitlines() if base.exists() else []
    drop = ("scene",) + tuple(CONFIG_OVERRIDES)
    lines = [ln for ln in lines if ln.split(":")[0].strip() not in drop]
    path = Path(folder) / "server.pbtxt"
    path.write_text("\n".join(lines + ["%s: %s" % kv for kv in CONFIG_OVERRIDES.items()]) + "\n")
    return path


def _child_setup():
    # Ray's worker threads block SIGINT, and a child inherits the mask: the
    # server would never see the SIGINT that stops it cleanly
    signal.pthread_sigmask(signal.SIG_SETMASK, [])
    # a worker killed by SIGKILL (or by Ray) must not leave its server running;
    # its world is of no use to anyone then, so no clean shutdown is owed
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


class OwnedServer:
    """Starts the server at construction; ``client`` is connected to it."""

    def __init__(self, timeout=10.0):
        binary = server_binary()
        if not binary.exists():
            raise FileNotFoundError("%s is not built (run `make`, or set CONTACTSIM_BUILD_DIR)" % binary)
        self.workdir = tempfile.mkdtemp(prefix="contactsim-fleet-")
        self.url = private_url()
        self.prefix = "FLEET_" + uuid.uuid4().hex[:10]
        scene = Path(self.workdir) / "empty.pbtxt"
        scene.write_text("gravity { z: -9.81 }\n")
        self.cmd = [str(binary), "--config", str(_write_config(self.workdir)), "--scene", str(scene),
                    "--lcm-url", self.url, "--prefix", self.prefix, "--mode", "free_run", "--paused",
                    "--no-live-line"]
        # subscribe first, so that the server's first STATUS is heard
        self.client = Client(url=self.url, prefix=self.prefix, timeout=timeout)
        self._log = open(Path(self.workdir) / "server.log", "wb")
        self.proc = subprocess.Popen(self.cmd, stdout=self._log, stderr=subprocess.STDOUT,
                                     stdin=subprocess.DEVNULL, preexec_fn=_child_setup)
        try:
            self.client.wait_for_server(timeout=START_TIMEOUT)
        except TimeoutError:
            self.stop()
            raise RuntimeError("contactsim-server gave no STATUS within %gs: %s\n%s" % (
                START_TIMEOUT, " ".join(self.cmd), self.log_tail()))

    @property
    def pid(self):
        return self.proc.pid

    def alive(self):
        return self.proc.poll() is None

    def log_tail(self, n=2000):
        try:
            return (Path(self.workdir) / "server.log").read_text(errors="replace")[-n:]
        except OSError:
            return ""

    def stop(self):
        """SIGINT, then SIGKILL after EXIT_TIMEOUT; returns the exit code."""
        self.client.close()
        interrupt(self.proc, EXIT_TIMEOUT)
        self._log.close()
        return self.proc.returncode
