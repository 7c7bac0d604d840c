"""What the tests of Drake's arm drivers share (test_iiwa_driver.py,
test_panda_driver.py): a tap on the driver's status and the server's
replies, and a run of examples/drake_arm_controller.py, Drake's own driver
systems in a process of their own, as a user runs them."""
import json
import subprocess
import sys
import threading
import time

import lcm

import contactsim
from conftest import REPO

CONTROLLER = REPO / "examples" / "drake_arm_controller.py"


class Tap:
    """Every status of type `status_cls` on `channel` and every reply_t heard
    on the server's LCM URL."""

    def __init__(self, server, channel, status_cls):
        self.lc = lcm.LCM(server.url)
        self.statuses, self.replies = [], []
        self.lc.subscribe(channel, lambda c, d: self.statuses.append(status_cls.decode(d)))
        self.lc.subscribe(server.prefix + "_REPLY", lambda c, d: self.replies.append(contactsim.reply_t.decode(d)))
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self):
        while not self._stop.is_set():
            self.lc.handle_timeout(20)

    def wait(self, what, timeout=10.0):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if what():
                return True
            time.sleep(0.01)
        return False

    def reply_to(self, utime, server):
        """The reply naming the command of this utime; fails after 10 s."""
        assert self.wait(lambda: any(r.request_id == utime for r in self.replies)), server.log()
        return [r for r in self.replies if r.request_id == utime][0]

    def close(self):
        self._stop.set()
        self._thread.join(2)


def run_controller(server, arm, seconds, *args):
    """Runs the example controller for `arm` ("iiwa", "panda") for `seconds`
    and returns its report."""
    done = subprocess.run([sys.executable, str(CONTROLLER), "--arm", arm, "--lcm-url", server.url, "--seconds",
                           str(seconds), "--report", *map(str, args)], capture_output=True, text=True,
                          timeout=seconds + 60)
    assert done.returncode == 0, done.stderr + "\nserver log:\n" + server.log()
    return json.loads(done.stdout.strip().splitlines()[-1])
