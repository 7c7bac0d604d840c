"""Signed commands against the real server started with --auth-key-file
(docs/protocol.md, "Authentication"): a signed client drives it, including
a lockstep controller; unsigned, forged, replayed and stale commands are
refused UNAUTHENTICATED, counted in STATUS, and change nothing; a restarted
client and a restarted server carry on; the server's output is signed."""
import time

import lcm
import pytest

import contactsim
from contactsim import auth, body_cmd_t

KEY = b"fedcba9876543210" * 4


@pytest.fixture
def key_file(tmp_path):
    path = tmp_path / "auth.key"
    path.write_bytes(KEY + b"\n")
    return path


def _client(server, key_file, client_id=None):
    return contactsim.Client(url=server.url, prefix=server.prefix, timeout=5.0,
                             auth_key_file=str(key_file) if key_file else "", client_id=client_id)


def _add_payload(client_id, request_id, x):
    m = body_cmd_t()
    m.client_id, m.request_id, m.op = client_id, request_id, body_cmd_t.ADD
    m.shape, m.radius, m.density = body_cmd_t.SPHERE, 0.1, 1000.0
    m.position, m.orientation = [x, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0]
    return m.encode()


def _replies_to(server, client_id, send, count, timeout=5.0):
    """Publishes with send(lc) and collects `count` replies to client_id."""
    got = []
    lc = lcm.LCM(server.url)
    sub = lc.subscribe(server.prefix + "_REPLY",
                       lambda ch, data: got.append(contactsim.reply_t.decode(data)))
    send(lc)
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and len([r for r in got if r.client_id == client_id]) < count:
        lc.handle_timeout(50)
    lc.unsubscribe(sub)
    return [r for r in got if r.client_id == client_id]


def test_signed_clients_drive_a_signing_server_and_others_are_refused(launch, key_file, tmp_path):
    s = launch(args=("--auth-key-file", str(key_file)))
    signed = _client(s, key_file)
    signed.wait_for_server()
    ball = signed.add_sphere(0.1, position=(0, 0, 1), density=1000)
    signed.step(10)
    assert signed.state().step == 10 and ball in signed.state().bodies
    assert signed.auth_failures == 0  # every STATE, STATUS and REPLY it read was the server's

    unsigned = _client(s, None)
    with pytest.raises(contactsim.CommandError) as e:
        unsigned.add_sphere(0.1, position=(1, 0, 1), density=1000)
    assert e.value.code_name == "UNAUTHENTICATED"
    assert "commands must be signed" in e.value.message

    wrong = tmp_path / "wrong.key"
    wrong.write_bytes(b"0" * 64)
    forger = _client(s, wrong)
    with pytest.raises(contactsim.TimeoutError):  # its reply is signed with the real key: dropped
        forger.add_sphere(0.1, position=(2, 0, 1), density=1000)
    assert forger.auth_failures > 0

    st = signed.wait_for_status(lambda x: x.commands_unauthenticated >= 2, timeout=5.0)
    assert "forged" in st.last_error or "must be signed" in st.last_error
    assert sorted(signed.state().bodies) == [ball]
    for c in (signed, unsigned, forger):
        c.close()


def test_replayed_and_stale_commands_are_refused(launch, key_file):
    s = launch(args=("--auth-key-file", str(key_file)))
    channel = s.prefix + "_BODY_CMD"
    signer = auth.Signer(KEY)
    packet = signer.sign(channel, _add_payload("replayer", 1, 0.0))
    replies = _replies_to(s, "replayer", lambda lc: (lc.publish(channel, packet), lc.publish(channel, packet)), 2)
    # the refusal is answered at once, the command at the next step boundary
    assert sorted(r.code for r in replies) == [0, contactsim.reply_t.UNAUTHENTICATED]
    assert any("replayed" in r.message for r in replies)

    old = auth.trailer(KEY, channel, _add_payload("stale", 1, 1.0), time.time_ns() - int(120e9))
    stale = _add_payload("stale", 1, 1.0) + old
    replies = _replies_to(s, "stale", lambda lc: lc.publish(channel, stale), 1)
    assert replies[0].code == contactsim.reply_t.UNAUTHENTICATED and "stale" in replies[0].message
    assert len(s.client.state().bodies) == 1


def test_a_restarted_client_and_a_restarted_server_carry_on(launch, key_file, tmp_path):
    journal = tmp_path / "journal"
    s = launch(args=("--auth-key-file", str(key_file), "--journal", str(journal)))
    first = _client(s, key_file, client_id="robot")
    first.add_sphere(0.1, position=(0, 0, 1), density=1000)
    first.close()
    # same client id, fresh process state: its seqs continue from the clock
    second = _client(s, key_file, client_id="robot")
    second.add_sphere(0.1, position=(1, 0, 1), density=1000)
    second.close()
    s.stop()

    s2 = launch(args=("--auth-key-file", str(key_file), "--journal", str(journal)))
    third = _client(s2, key_file, client_id="robot")
    third.wait_for_server()
    third.add_sphere(0.1, position=(2, 0, 1), density=1000)
    assert len(third.state().bodies) == 3
    third.close()
