"""Runs the stock ``lcm-logger`` for a test (test_logged_channels.py, test_replay.py).

    with LcmRecorder(url, "PREFIX_.*", path):
        ... drive the server ...
    # path now holds the complete log

On entry the logger is started and the test waits until it provably records:
probe messages are published, with retries, until one is in the file (the
logger gives no "ready" signal, and a message sent before it subscribed would
be lost silently). On exit another probe is awaited in the file, so that
everything published before it is written, and the logger gets SIGINT.

``sync()`` is the same barrier mid-run: a test that publishes in bursts waits
for the logger to drain each one, since the logger (like any LCM subscriber)
keeps only 30 undelivered messages and drops the rest when a loaded machine
deschedules it.
"""
import shutil
import subprocess
import sys
import time
from pathlib import Path

import lcm

from contactsim.process import interrupt

READY_TIMEOUT = 15.0   # two shared cores: starting a process can take seconds
EXIT_TIMEOUT = 10.0


def lcm_tool(name):
    """Path of an LCM command-line tool: on PATH (liblcm-bin) or beside this Python (the lcm wheel)."""
    found = shutil.which(name)
    if found:
        return found
    beside = Path(sys.executable).parent / name
    return str(beside) if beside.exists() else None


class LcmRecorder:
    def __init__(self, url, channels, path):
        self.url, self.channels, self.path = url, channels, Path(path)
        self.probe_channel = channels.replace(".*", "") + "RECORDER_PROBE"
        self.proc = None
        self.syncs = 0

    def __enter__(self):
        tool = lcm_tool("lcm-logger")
        if tool is None:
            import pytest
            pytest.skip("lcm-logger is not installed (make deps)")
        self.proc = subprocess.Popen([tool, "-q", "-f", "--flush-interval=20", "--lcm-url=" + self.url, "-c", self.channels,
                                      str(self.path)], stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                     stderr=subprocess.STDOUT)
        self.lc = lcm.LCM(self.url)
        if not self._probe(b"start"):
            out = self.proc.stdout.read().decode(errors="replace") if self.proc.poll() is not None else ""
            self.__exit__(None, None, None)
            raise RuntimeError("lcm-logger recorded nothing within %gs: %s" % (READY_TIMEOUT, out))
        return self

    def sync(self):
        """Returns once everything published before the call is in the file."""
        self.syncs += 1
        if not self._probe(b"sync-%d" % self.syncs):
            raise RuntimeError("lcm-logger did not record a probe within %gs" % READY_TIMEOUT)

    def _probe(self, tag):
        """Publishes a probe (again every 0.1 s) until the file holds it."""
        payload = b"recorder-probe-" + tag
        deadline = time.monotonic() + READY_TIMEOUT
        while self.proc.poll() is None and time.monotonic() < deadline:
            self.lc.publish(self.probe_channel, payload)
            time.sleep(0.1)
            if self.path.exists() and payload in self.path.read_bytes():
                return True
        return False

    def __exit__(self, *exc):
        # a barrier: what the server published before this probe (all of it,
        # once the test has its last reply) is in the file when the probe is
        if self.proc is not None and self.proc.poll() is None:
            self._probe(b"end")
        if self.proc is not None:
            interrupt(self.proc, EXIT_TIMEOUT)
        return False
