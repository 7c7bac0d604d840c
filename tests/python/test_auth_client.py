"""The Python client with an auth key (docs/protocol.md, "Authentication")
against the pure-Python fake server made to sign and check like the real
one: commands and lockstep inputs go out signed, server output that fails
its check is dropped and counted, and a client without a key still reads
signed output. No contactsim-server binary needed."""
import subprocess
import sys
import time

import pytest

import contactsim
from contactsim import auth

from conftest import REPLY_TIMEOUT, FakeServer

KEY = b"0123456789abcdef" * 4


class _SigningLcm:
    """An lcm.LCM whose publish signs with `signer` (None: sends unsigned)."""

    def __init__(self, lc, signer):
        self._lc = lc
        self.signer = signer

    def publish(self, channel, data):
        self._lc.publish(channel, self.signer.sign(channel, data) if self.signer else data)

    def __getattr__(self, name):
        return getattr(self._lc, name)


class SigningFakeServer(FakeServer):
    """FakeServer that signs what it publishes with `key` and checks every
    command and input as the server does (mac, freshness, replay per client
    id), recording refusals in `refused` instead of answering them."""

    def __init__(self, key=KEY):
        super().__init__()
        self.key = key
        self.lc = _SigningLcm(self.lc, auth.Signer(key))
        self.replay = auth.ReplayWindow()
        self.refused = []
        self.inputs = []
        self.lc.subscribe(self.prefix + "_INPUT", self._on_input)

    def _admit(self, channel, data, msg_type):
        v = auth.verify(self.key, channel, data)
        if not v.ok:
            self.refused.append(v.error)
            return None
        msg = msg_type.decode(data[:v.payload_size])
        ok, why = self.replay.accept(msg.client_id, v.seq, time.time_ns())
        if not ok:
            self.refused.append(why)
            return None
        return msg

    def _on_body(self, channel, data):
        m = self._admit(channel, data, contactsim.body_cmd_t)
        if m is not None:
            self._handle(m, is_add=m.op == contactsim.body_cmd_t.ADD)

    def _on_scene(self, channel, data):
        m = self._admit(channel, data, contactsim.scene_cmd_t)
        if m is not None:
            self._handle(m, steps=m.steps if m.op == contactsim.scene_cmd_t.STEP else 0)

    def _on_input(self, channel, data):
        m = self._admit(channel, data, contactsim.input_t)
        if m is not None:
            self.inputs.append(m)


@pytest.fixture
def key_file(tmp_path):
    p = tmp_path / "auth.key"
    p.write_bytes(KEY + b"\n")
    return p


@pytest.fixture
def signing_server():
    fs = SigningFakeServer()
    yield fs
    fs.close()


def connect(server, **kw):
    return contactsim.Client(url=server.url, prefix=server.prefix, timeout=kw.pop("timeout", REPLY_TIMEOUT), **kw)


def test_signed_commands_and_signed_output_work_end_to_end(signing_server, key_file):
    with connect(signing_server, auth_key_file=key_file) as c:
        assert c.signs
        assert c.add_sphere(0.1) == 1
        reply = c.step(3)
        assert reply.step == 3 and c.state().step == 3
    assert signing_server.refused == [] and len(signing_server.commands) == 2


def test_key_file_comes_from_the_environment(signing_server, key_file, monkeypatch):
    monkeypatch.setenv(auth.KEY_FILE_ENV, str(key_file))
    with connect(signing_server) as c:
        assert c.signs
        c.pause()
    with connect(signing_server, auth_key_file="") as c:  # "" turns signing off
        assert not c.signs


def test_unsigned_commands_are_refused_by_a_signing_server(signing_server):
    with connect(signing_server, auth_key_file="", timeout=0.5) as c:
        with pytest.raises(contactsim.TimeoutError):
            c.pause()
    assert signing_server.refused and signing_server.refused[0].startswith("unsigned:")


def test_output_with_another_key_is_dropped_and_counted(signing_server, tmp_path):
    other = tmp_path / "other.key"
    other.write_bytes(b"another key of at least 32 bytes....")
    with connect(signing_server, auth_key_file=other, timeout=0.5) as c:
        signing_server.publish_status()
        with pytest.raises(contactsim.TimeoutError, match="failed their signature check"):
            c.wait_for_server(timeout=0.5)
        assert c.auth_failures >= 1
        assert c.last_auth_failure.startswith(signing_server.prefix + "_STATUS: forged:")


def test_unsigned_output_is_dropped_by_a_signing_client(signing_server, key_file):
    signing_server.lc.signer = None
    with connect(signing_server, auth_key_file=key_file) as c:
        signing_server.publish_state(5)
        signing_server.publish_status()
        with pytest.raises(contactsim.TimeoutError):
            c.wait_for_state(timeout=0.5)
        assert c.state() is None and c.status() is None
        assert c.auth_failures >= 2 and "unsigned:" in c.last_auth_failure


def test_replayed_output_is_dropped(signing_server, key_file):
    with connect(signing_server, auth_key_file=key_file) as c:
        m = contactsim.status_t()
        m.version = "fake"
        signed = signing_server.lc.signer.sign(signing_server.prefix + "_STATUS", m.encode())
        signing_server.lc._lc.publish(signing_server.prefix + "_STATUS", signed)
        c.wait_for_server(timeout=REPLY_TIMEOUT)
        signing_server.lc._lc.publish(signing_server.prefix + "_STATUS", signed)
        deadline = time.monotonic() + REPLY_TIMEOUT
        while c.auth_failures == 0 and time.monotonic() < deadline:
            time.sleep(0.01)
        assert c.auth_failures == 1 and "replayed:" in c.last_auth_failure


def test_client_without_a_key_reads_signed_output(signing_server):
    with connect(signing_server, auth_key_file="") as c:
        signing_server.publish_status(num_bodies=4)
        assert c.wait_for_server(timeout=REPLY_TIMEOUT).num_bodies == 4
        signing_server.publish_state(9)
        assert c.wait_for_state(lambda s: s.step == 9, timeout=REPLY_TIMEOUT).step == 9


def test_lockstep_inputs_are_signed(signing_server, key_file):
    with connect(signing_server, auth_key_file=key_file) as c:
        c.send_input(1, {1: (0, 0, 9.81)})
        ctl = contactsim.Controller(c, lambda state: {1: (0, 0, 1)})
        ctl.start()
        signing_server.publish_state(1)
        ctl.wait_for_step(1, timeout=REPLY_TIMEOUT)
        ctl.stop()
        deadline = time.monotonic() + REPLY_TIMEOUT
        while len(signing_server.inputs) < 2 and time.monotonic() < deadline:
            time.sleep(0.01)
    assert [m.step for m in signing_server.inputs] == [1, 2]
    assert signing_server.refused == []


def test_bad_key_file_raises_before_anything_is_sent(tmp_path):
    with pytest.raises(contactsim.AuthKeyError, match="missing.key"):
        contactsim.Client(auth_key_file=tmp_path / "missing.key")


def test_cli_takes_the_key_file_and_reports_a_bad_one(signing_server, key_file, tmp_path):
    base = [sys.executable, "-m", "contactsim.cli", "--lcm-url", signing_server.url,
            "--prefix", signing_server.prefix, "--timeout", str(REPLY_TIMEOUT)]
    ok = subprocess.run(base + ["--auth-key-file", str(key_file), "pause"], capture_output=True, text=True,
                        timeout=60)
    assert ok.returncode == 0, ok.stderr
    bad = subprocess.run(base + ["--auth-key-file", str(tmp_path / "nope.key"), "pause"], capture_output=True,
                         text=True, timeout=60)
    assert bad.returncode == 2 and "nope.key" in bad.stderr


# Verifies that with a key an observer sees another client's RAY_CAST (by
# its mac; a forged one is dropped) and every RAY_HITS through the client's
# own check, once, without counting a failure: two subscriptions checking
# the same signed message would see its seq twice.
def test_observers_see_signed_ray_casts_and_hits(signing_server, key_file):
    def cast_msg(request_id):
        m = contactsim.ray_cast_t()
        m.client_id, m.request_id, m.num_rays = "other", request_id, 1
        m.origins, m.directions, m.max_distances = [[0.0, 0.0, 0.0]], [[1.0, 0.0, 0.0]], [1.0]
        return m.encode()

    with connect(signing_server, auth_key_file=key_file) as c:
        casts, hits = [], []
        c.on_command("RAY_CAST", contactsim.ray_cast_t, casts.append)
        c.on_ray_hits(hits.append)
        channel = signing_server.prefix + "_RAY_CAST"
        raw = signing_server.lc._lc   # unsigned: the other client signs for itself
        raw.publish(channel, auth.Signer(b"another key, not the server's!!" * 2).sign(channel, cast_msg(6)))
        raw.publish(channel, auth.Signer(KEY).sign(channel, cast_msg(7)))
        answer = contactsim.ray_hits_t()
        answer.client_id, answer.request_id, answer.num_rays = "other", 7, 1
        answer.hit, answer.body_ids, answer.distances = [True], [1], [0.5]
        answer.points, answer.normals = [[0.5, 0.0, 0.0]], [[-1.0, 0.0, 0.0]]
        signing_server.lc.publish(signing_server.prefix + "_RAY_HITS", answer.encode())
        deadline = time.monotonic() + REPLY_TIMEOUT
        while (not casts or not hits) and time.monotonic() < deadline:
            time.sleep(0.01)
        time.sleep(0.1)   # a forged cast, or a second delivery, would have come by now
        assert [m.request_id for m in casts] == [7] and [m.request_id for m in hits] == [7]
        assert c.auth_failures == 0, c.last_auth_failure
        with pytest.raises(ValueError):
            c.on_command("STATE", contactsim.state_t, casts.append)
