"""Stopping a child process the way the server and lcm-logger expect: SIGINT
(they finish what they write and exit 0), then SIGKILL when it is ignored.
Shared by the fleet's private servers, the test fixtures and the
reliability scripts."""
import signal
import subprocess


def interrupt(proc, timeout):
    """SIGINT to ``proc`` (a ``subprocess.Popen``) if it still runs, waits up
    to ``timeout`` seconds, then SIGKILL. Returns True when it had to be
    killed."""
    if proc.poll() is not None:
        return False
    proc.send_signal(signal.SIGINT)
    try:
        proc.wait(timeout)
        return False
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
        return True
