"""A contactsim-viewer child process for the viewer's tests and scripts
(tests/python/test_viewer.py, bench/scripts/viewer_bench.py,
scripts/viewer_screenshot.py), beside headless.py's browser.

    with ViewerProcess(["--lcm-url", url, "--prefix", prefix]) as v:
        driver.get(v.url)

Starts ``python -m contactsim.viewer --port 0`` with this copy of the
package first on PYTHONPATH (the .venv may hold another checkout editable),
reads the URL it prints, and stops it with SIGINT (SIGKILL after 10 s).
"""
import os
import subprocess
import sys
import threading
from pathlib import Path

from ..process import interrupt

PACKAGE_PARENT = Path(__file__).resolve().parents[2]  # the folder that holds contactsim/
START_TIMEOUT = 20.0
STOP_TIMEOUT = 10.0


class ViewerProcess:
    def __init__(self, args):
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(
            [str(PACKAGE_PARENT), os.environ.get("PYTHONPATH", "")]))
        self.proc = subprocess.Popen([sys.executable, "-m", "contactsim.viewer", "--port", "0", *args], env=env,
                                     stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     text=True)
        self.output = []
        self.url = None
        ready = threading.Event()

        def read():
            for line in self.proc.stdout:
                self.output.append(line)
                if self.url is None and line.startswith("contactsim-viewer: http"):
                    self.url = line.split()[1]
                    ready.set()
            ready.set()
        threading.Thread(target=read, daemon=True).start()
        if not ready.wait(START_TIMEOUT) or self.url is None:
            self.stop()
            raise RuntimeError("contactsim-viewer printed no URL:\n" + "".join(self.output))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()

    def stop(self):
        interrupt(self.proc, STOP_TIMEOUT)
        return self.proc.returncode
