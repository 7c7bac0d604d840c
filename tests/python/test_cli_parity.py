"""The two CLIs agree: the same subcommands, one table of mode names each,
and those tables are the server's (docs/packaging.md).

contactsim-ctl (C++) and contactsim-py (Python) are driven the same way by
scripts; the run-mode names live once per language (kRunModeNames in
service/server/command.h for the server, kModeNames in
clients/cpp/include/contactsim/mode_names.h for the C++ client, MODE_NAMES
in contactsim/state.py), and the tables are compared here.
"""
import re
import subprocess

import pytest

import contactsim
from contactsim import cli as py_cli
from contactsim.client import MODES
from contactsim.state import MODE_NAMES

from conftest import BUILD, REPO
from test_cli import cli

CTL = BUILD / "bin" / "contactsim-ctl"


def _cpp_table(path, pattern):
    """{value name: mode name} of a C++ table's rows, e.g. {"LOCKSTEP": "lockstep"}."""
    return dict(re.findall(pattern, (REPO / path).read_text()))


def test_mode_tables_are_the_servers():
    server = _cpp_table("service/server/command.h", r'\{RunMode::k(\w+), "(\w+)"\}')
    client = _cpp_table("clients/cpp/include/contactsim/mode_names.h", r'\{status_t::(\w+), "(\w+)"\}')
    names = sorted(server.values())
    assert names == sorted(client.values()) == sorted(MODE_NAMES.values()) == sorted(MODES)
    # the server's enum values are the wire's, whose constant names the C++ table uses
    enum = dict(re.findall(r"k(\w+) = (\d+)", (REPO / "service/server/command.h").read_text()
                           .split("enum class RunMode")[1].split("}")[0]))
    for const, name in client.items():
        value = getattr(contactsim.status_t, const)
        assert MODE_NAMES[value] == name and value == getattr(contactsim.scene_cmd_t, const)
        assert [int(v) for k, v in enum.items() if server[k] == name] == [value]


def _ctl_subcommands(*path):
    if not CTL.exists():
        pytest.skip("%s is not built" % CTL)
    out = subprocess.run([str(CTL), *path, "--help"], capture_output=True, text=True, timeout=10).stdout
    return sorted(re.findall(r"^  (\w+)\s", out.split("Subcommands:")[1], re.M))


def _py_subcommands(*path):
    parser = py_cli._parser()
    for name in path:
        parser = next(a for a in parser._actions if a.dest == "cmd" and a.choices).choices[name]
    action = next(a for a in parser._actions if a.choices and a.dest in ("cmd", "joint_cmd", "shape", "sensor_cmd"))
    return sorted(action.choices)


def test_the_clis_have_the_same_subcommands():
    # compare runs a fleet of servers on Ray (docs/fleet.md): Python's alone
    assert sorted(set(_py_subcommands()) - {"compare"}) == _ctl_subcommands()
    assert _py_subcommands("joint") == _ctl_subcommands("joint")
    assert _py_subcommands("add") == _ctl_subcommands("add")
    assert _py_subcommands("sensor") == _ctl_subcommands("sensor")


def test_python_cli_joints_and_lockstep_status(server):
    c = server.client
    bob = c.add_sphere(0.1, position=(0, 0, 1), mass=1.0)
    r = cli(server, "joint", "add", "distance", str(bob), "--anchor", "0", "0", "2")
    assert r.returncode == 0 and r.stdout.strip() == "1", r.stdout + r.stderr
    r = cli(server, "joint", "add", "hinge", str(bob), "--anchor", "0", "0", "1")
    assert r.returncode == 1 and "axis" in r.stderr, r.stdout + r.stderr
    assert cli(server, "joint", "remove", "1").returncode == 0
    c.set_mode("lockstep")
    status = c.wait_for_status(lambda s: s.mode == "lockstep", timeout=5)
    assert status.mode == "lockstep"
    r = cli(server, "status")
    assert re.search(r"^mode\s+lockstep$", r.stdout, re.M), r.stdout + r.stderr
    # the active method's contract (docs/physics.md, "Method contract")
    assert re.search(r"^method_contract\s+joints=yes; restitution=yes; kinematic=yes; contact_forces=yes; friction=coulomb disk$",
                     r.stdout, re.M), r.stdout


def test_ctl_names_the_lockstep_mode(server):
    if not CTL.exists():
        pytest.skip("%s is not built" % CTL)
    server.client.set_mode("lockstep")
    server.client.wait_for_status(lambda s: s.mode == "lockstep", timeout=5)
    r = subprocess.run([str(CTL), "--lcm-url", server.url, "--prefix", server.prefix, "status"],
                       capture_output=True, text=True, timeout=30)
    assert r.returncode == 0 and "mode: lockstep" in r.stdout, r.stdout + r.stderr
    assert "\nmethod_contract: joints=yes; restitution=yes; kinematic=yes; contact_forces=yes; friction=coulomb disk\n" in r.stdout, r.stdout
