"""A contactsim-server child process for the reliability scripts (soak.py,
flood.py, bad_input_table.py), outside pytest.

    with ServerProcess(build_dir, scene_text=SCENE, args=["--journal", d]) as srv:
        srv.client.step(10)
        print(srv.rss_kib())

Like tests/python/conftest.py it starts the real binary on config/server.pbtxt
(or another config), free_run and paused, on a multicast port and channel
prefix of its own on loopback (ttl=0), waits for the first STATUS and
connects a contactsim.Client. ``config_overrides`` ({field: text value})
writes a copy of config/server.pbtxt with those fields set. On exit it sends SIGINT and reports the exit
status (``returncode``), SIGKILL after 10 s.
"""
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "clients" / "python"))

import contactsim  # noqa: E402
from contactsim.process import interrupt  # noqa: E402

CONFIG = REPO / "config" / "server.pbtxt"
START_TIMEOUT = 30.0
EXIT_TIMEOUT = 10.0


def server_binary(build_dir=None):
    if os.environ.get("CONTACTSIM_SERVER"):
        return Path(os.environ["CONTACTSIM_SERVER"])
    build = Path(build_dir or os.environ.get("CONTACTSIM_BUILD_DIR") or REPO / "build")
    return build.resolve() / "bin" / "contactsim-server"


def endpoint(tag, base_port=9800):
    """(url, prefix): a port in [base_port, base_port + 1000) and a prefix
    from the pid, so that parallel runs and the test suites keep apart."""
    port = base_port + (os.getpid() * 13) % 1000
    return ("udpm://239.255.76.67:%d?ttl=0&recv_buf_size=8388608" % port, "%s%d" % (tag, os.getpid()))


def rss_kib(pid):
    """VmRSS of a process, KiB (None once it is gone)."""
    try:
        for line in Path("/proc/%d/status" % pid).read_text().splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    except OSError:
        return None
    return None


class ServerProcess:
    def __init__(self, build_dir=None, scene_text="gravity { z: -9.81 }\n", config=None, args=(), tag="REL",
                 workdir=None, timeout=5.0, url=None, prefix=None, config_overrides=None):
        self.binary = server_binary(build_dir)
        if not self.binary.exists():
            raise FileNotFoundError("%s is not built (make, or --build-dir)" % self.binary)
        self._tmp = None
        if workdir is None:
            self._tmp = tempfile.TemporaryDirectory(prefix="contactsim-%s-" % tag.lower())
            workdir = self._tmp.name
        self.workdir = Path(workdir)
        default_url, default_prefix = endpoint(tag)
        self.url, self.prefix = url or default_url, prefix or default_prefix
        self.scene = self.workdir / "scene.pbtxt"
        self.scene.write_text(scene_text)
        self.config = Path(config or CONFIG)
        if config_overrides:
            # the default config with some fields replaced
            self.config = self.workdir / "server.pbtxt"
            drop = ("scene",) + tuple(config_overrides)
            lines = [ln for ln in CONFIG.read_text().splitlines() if ln.split(":")[0].strip() not in drop]
            self.config.write_text("\n".join(lines + ["%s: %s" % kv for kv in config_overrides.items()]) + "\n")
        self.log_path = self.workdir / "server.log"
        self.cmd = [str(self.binary), "--config", str(self.config), "--scene", str(self.scene),
                    "--lcm-url", self.url, "--mode", "free_run", "--paused", "--no-live-line",
                    "--prefix", self.prefix, *args]
        self.timeout = timeout
        self.proc = None
        self.client = None
        self.returncode = None

    def start(self):
        self.client = contactsim.Client(url=self.url, prefix=self.prefix, timeout=self.timeout)
        self._log = open(self.log_path, "wb")
        self.proc = subprocess.Popen(self.cmd, stdout=self._log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
        try:
            self.client.wait_for_server(timeout=START_TIMEOUT)
        except contactsim.TimeoutError:
            self.stop()
            raise RuntimeError("server gave no STATUS within %gs (exit %s):\n%s" % (
                START_TIMEOUT, self.returncode, self.log_tail()))
        return self

    @property
    def pid(self):
        return self.proc.pid

    def alive(self):
        return self.proc is not None and self.proc.poll() is None

    def rss_kib(self):
        return rss_kib(self.proc.pid)

    def log_tail(self, n=4000):
        try:
            return self.log_path.read_text(errors="replace")[-n:]
        except OSError:
            return ""

    def stop(self):
        """SIGINT, then SIGKILL after EXIT_TIMEOUT; returns the exit code
        (-9 when it had to be killed)."""
        if self.client is not None:
            self.client.close()
        if self.proc is not None:
            interrupt(self.proc, EXIT_TIMEOUT)
            self.returncode = self.proc.returncode
            self._log.close()
        return self.returncode

    def cleanup(self):
        if self._tmp is not None:
            self._tmp.cleanup()

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()
        return False


def wait_until(predicate, timeout, period=0.01):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(period)
    return predicate()
