"""Fixtures of the Python client tests.

* ``launch(scene=None, args=(), wrapper=(), config=None)``: starts the REAL contactsim-server
  ($CONTACTSIM_BUILD_DIR/bin/contactsim-server, or $CONTACTSIM_SERVER) with
  config/server.pbtxt (or ``config``), a scene (default: an empty one with gravity), its own
  multicast port (8800-9799; the C++ integration tests use 7800-8799) and its
  own channel prefix, in free_run mode and paused; waits for its first STATUS
  and returns a Server whose ``client`` is connected. At teardown each server
  gets SIGINT (then SIGKILL after 10 s) and must have exited with status 0.
* ``server`` / ``client``: one launched server and its Client.
* ``fake_server``: a pure-Python stand-in replying to commands, for tests of
  the client alone (no binary needed).
"""
import importlib.util
import itertools
import os
import re
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "clients" / "python"))
BUILD = Path(os.environ.get("CONTACTSIM_BUILD_DIR") or (REPO / "build")).resolve()
os.environ["CONTACTSIM_BUILD_DIR"] = str(BUILD)
# Clients sign when this is set (docs/protocol.md, "Authentication"); the
# tests' servers have no key, and the auth tests pass theirs explicitly.
os.environ.pop("CONTACTSIM_AUTH_KEY_FILE", None)
SERVER_BIN = Path(os.environ.get("CONTACTSIM_SERVER") or (BUILD / "bin" / "contactsim-server"))
CONFIG = REPO / "config" / "server.pbtxt"
EMPTY_SCENE = "gravity { z: -9.81 }\n"

import lcm  # noqa: E402
import contactsim  # noqa: E402
from contactsim.process import interrupt  # noqa: E402

START_TIMEOUT = 15.0   # two cores shared with builds and other test runs
REPLY_TIMEOUT = 5.0
EXIT_TIMEOUT = 10.0

_counter = itertools.count()


def current_state(client, gravity):
    """The STATE of the world as it is, without a step: a paused server
    publishes STATE after a command that changes the world, and SET_GRAVITY
    counts as one even when it sets the gravity the world has (``gravity``)."""
    got = []
    arrived = threading.Event()
    remove = client.on_state(lambda s: (got.append(s), arrived.set()))
    try:
        client.set_gravity(gravity)
        assert arrived.wait(10.0), "no STATE after SET_GRAVITY"
    finally:
        remove()
    return got[-1]


def load_script(path):
    """A program of the repository (``path`` relative to it, e.g.
    bench/scripts/bench_scenes.py) as a module, for testing its functions;
    scripts are not modules of any package, so they are loaded by path."""
    path = REPO / path
    spec = importlib.util.spec_from_file_location(path.stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def unique_endpoint(tag="PY"):
    """(url, prefix) distinct per process and per call: even when two ports
    collide across processes, the prefixes differ."""
    n = next(_counter)
    port = 8800 + (os.getpid() * 7 + n) % 1000
    return ("udpm://239.255.76.67:%d?ttl=0&recv_buf_size=8388608" % port,
            "%s%d_%d" % (tag, os.getpid(), n))


class Server:
    """One contactsim-server child process and a Client connected to it."""

    def __init__(self, tmp_path, scene=None, args=(), wrapper=(), config=None):
        if not SERVER_BIN.exists():
            pytest.skip("%s is not built (run `make`)" % SERVER_BIN)
        self.url, self.prefix = unique_endpoint()
        if scene is None:
            scene = tmp_path / ("empty-%s.pbtxt" % self.prefix)
            scene.write_text(EMPTY_SCENE)
        self.scene = Path(scene)
        self.log_path = tmp_path / ("server-%s.log" % self.prefix)
        # wrapper: a command that execs the server, e.g. ("prlimit", "--fsize=N", "--")
        self.cmd = [*wrapper, str(SERVER_BIN), "--config", str(config or CONFIG), "--scene", str(self.scene),
                    "--lcm-url", self.url, "--mode", "free_run", "--paused", "--no-live-line",
                    "--prefix", self.prefix, *args]
        # Subscribe before the server starts, so that its first STATUS is heard.
        self.client = contactsim.Client(url=self.url, prefix=self.prefix, timeout=REPLY_TIMEOUT)
        self._log = open(self.log_path, "wb")
        self.proc = subprocess.Popen(self.cmd, stdout=self._log, stderr=subprocess.STDOUT,
                                     stdin=subprocess.DEVNULL)
        try:
            self.client.wait_for_server(timeout=START_TIMEOUT)
        except contactsim.TimeoutError:
            rc = self.proc.poll()
            self.stop(check=False)
            pytest.fail("server gave no STATUS within %gs (exit code %s)\n%s\nlog:\n%s" % (
                START_TIMEOUT, rc, " ".join(self.cmd), self.log()))

    def log(self):
        try:
            return self.log_path.read_text(errors="replace")[-4000:]
        except OSError:
            return ""

    def kill(self):
        """SIGKILL, as a crash: no clean shutdown, and stop() expects none."""
        self.client.close()
        self.proc.kill()
        self.proc.wait()
        self.killed = True

    def stop(self, check=True):
        """SIGINT, then SIGKILL after EXIT_TIMEOUT; returns the exit code."""
        if getattr(self, "killed", False):
            return self.proc.returncode
        self.client.close()
        killed = interrupt(self.proc, EXIT_TIMEOUT)
        self._log.close()
        rc = self.proc.returncode
        if check:
            assert not killed, "server ignored SIGINT for %gs\nlog:\n%s" % (EXIT_TIMEOUT, self.log())
            assert rc == 0, "server exited with %s\nlog:\n%s" % (rc, self.log())
        return rc


@pytest.fixture
def launch(tmp_path):
    servers = []

    def start(scene=None, args=(), wrapper=(), config=None):
        s = Server(tmp_path, scene, args, wrapper, config)
        servers.append(s)
        return s

    yield start
    errors = []
    for s in servers:
        try:
            s.stop()
        except AssertionError as e:
            errors.append(str(e))
    assert not errors, "\n".join(errors)


@pytest.fixture
def server(launch):
    return launch()


@pytest.fixture
def client(server):
    return server.client


# ---------------------------------------------------------------- fake server
class FakeServer:
    """Answers commands like the server would, without physics.

    Records every decoded command in ``commands``. ``behaviour(msg)`` may
    return None (reply OK) or (code, message) to reject; ``silent`` drops
    commands; ``reply_before_state`` sends a STEP's reply before its STATE
    (after ``state_delay`` s); ``decoy`` first sends a reply with another
    client id and the same request id.
    """

    def __init__(self):
        self.url, self.prefix = unique_endpoint("FAKE")
        self.channels = contactsim.protocol.channel_names(self.prefix)
        self.lc = lcm.LCM(self.url)
        self.commands = []
        self.behaviour = lambda msg: None
        self.silent = False
        self.reply_before_state = False
        self.state_delay = 0.0
        self.decoy = False
        self.step = 0
        self.next_id = 1
        self.lc.subscribe(self.channels["BODY_CMD"], self._on_body)
        self.lc.subscribe(self.channels["SCENE_CMD"], self._on_scene)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self):
        while not self._stop.is_set():
            self.lc.handle_timeout(20)

    def close(self):
        self._stop.set()
        self._thread.join(2)

    def publish_state(self, step, bodies=()):
        m = contactsim.state_t()
        m.time = step / 240.0
        m.step = step
        m.state_hash = step * 7919
        m.bodies = list(bodies)
        m.num_bodies = len(m.bodies)
        self.lc.publish(self.channels["STATE"], m.encode())

    def publish_status(self, **fields):
        m = contactsim.status_t()
        m.version = "fake"
        m.mode = 2
        for k, v in fields.items():
            setattr(m, k, v)
        self.lc.publish(self.channels["STATUS"], m.encode())

    def _reply(self, cmd, code=0, message="", ids=(), client_id=None):
        r = contactsim.reply_t()
        r.client_id = cmd.client_id if client_id is None else client_id
        r.request_id = cmd.request_id
        r.code = code
        r.message = message
        r.step = self.step
        r.time = self.step / 240.0
        r.ids = list(ids)
        r.num_ids = len(r.ids)
        self.lc.publish(self.channels["REPLY"], r.encode())

    def _handle(self, cmd, is_add=False, steps=0):
        self.commands.append(cmd)
        if self.silent:
            return
        if self.decoy:
            self._reply(cmd, 1, "decoy", client_id=cmd.client_id + "-other")
        verdict = self.behaviour(cmd)
        if verdict is not None:
            self._reply(cmd, *verdict)
            return
        ids = ()
        if is_add:
            ids, self.next_id = (self.next_id,), self.next_id + 1
        if steps:
            self.step += steps
            if self.reply_before_state:
                self._reply(cmd, ids=ids)
                time.sleep(self.state_delay)
                self.publish_state(self.step)
                return
            self.publish_state(self.step)
        self._reply(cmd, ids=ids)

    def _on_body(self, channel, data):
        m = contactsim.body_cmd_t.decode(data)
        self._handle(m, is_add=m.op == contactsim.body_cmd_t.ADD)

    def _on_scene(self, channel, data):
        m = contactsim.scene_cmd_t.decode(data)
        self._handle(m, steps=m.steps if m.op == contactsim.scene_cmd_t.STEP else 0)


@pytest.fixture
def fake_server():
    fs = FakeServer()
    yield fs
    fs.close()


@pytest.fixture
def fake_client(fake_server):
    with contactsim.Client(url=fake_server.url, prefix=fake_server.prefix, timeout=2.0) as c:
        yield c


def method_names(client):
    """Every registered contact method, from the server's own error message."""
    with pytest.raises(contactsim.CommandError) as e:
        client.set_contact_method("no-such-method")
    return re.search(r"known: ([^)]*)", str(e.value)).group(1).replace(",", " ").split()
