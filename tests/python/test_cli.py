"""The contactsim-py console script and the drop_ball example against the real server."""
import os
import re
import subprocess
import sys

import pytest

from conftest import REPO

ENV = dict(os.environ, PYTHONPATH=str(REPO / "clients" / "python"))


def cli(server, *args, timeout=30):
    cmd = [sys.executable, "-m", "contactsim.cli", "--lcm-url", server.url, "--prefix", server.prefix,
           "--timeout", "5", *args]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=ENV)


def test_cli_commands(server):
    r = cli(server, "status")
    assert r.returncode == 0 and re.search(r"^paused\s+True$", r.stdout, re.M), r.stdout + r.stderr
    r = cli(server, "add", "plane", "0", "0", "1", "0")
    assert r.returncode == 0 and r.stdout.strip() == "1", r.stderr
    r = cli(server, "add", "sphere", "0.1", "--position", "0", "0", "1", "--restitution", "0.5")
    assert r.returncode == 0 and r.stdout.strip() == "2", r.stderr
    r = cli(server, "add", "box", "0.1", "0.2", "0.3", "--mass", "3")
    assert r.returncode == 0 and r.stdout.strip() == "3", r.stderr
    assert cli(server, "remove", "3").returncode == 0
    r = cli(server, "step", "10")
    assert r.returncode == 0 and "step 10" in r.stdout, r.stdout + r.stderr
    assert cli(server, "method", "impulse", "iterations=12").returncode == 0
    assert cli(server, "resume").returncode == 0
    assert cli(server, "pause").returncode == 0
    assert cli(server, "reset").returncode == 0
    client = server.client
    client.step(1)
    assert client.state().step == 1 and not client.state().bodies


def test_cli_exit_codes(server):
    r = cli(server, "add", "sphere", "-1")
    assert r.returncode == 1 and "radius" in r.stderr
    r = cli(server, "remove", "42")
    assert r.returncode == 1 and "42" in r.stderr
    r = subprocess.run([sys.executable, "-m", "contactsim.cli", "--lcm-url", server.url, "--prefix",
                        "NOBODY_LISTENS", "--timeout", "0.3", "pause"],
                       capture_output=True, text=True, timeout=30, env=ENV)
    assert r.returncode == 2 and "no reply" in r.stderr


def test_drop_ball_example(server):
    r = subprocess.run([sys.executable, str(REPO / "clients" / "python" / "examples" / "drop_ball.py"),
                        "--lcm-url", server.url, "--prefix", server.prefix, "--seconds", "1.5"],
                       capture_output=True, text=True, timeout=120, env=ENV)
    assert r.returncode == 0, r.stderr
    apexes = [float(x) for x in re.findall(r"apex ([0-9.]+) m", r.stdout)]
    assert apexes and apexes[0] == pytest.approx(0.25, rel=0.02), r.stdout
