"""Signed messages in Python (contactsim.auth): the wire format against the
pinned test vector (tests/client/signature_test.cpp pins the same), every
way a message can fail, the anti-replay window, key files, and byte for byte
agreement with the C++ library (contactsim-auth-sign). No server needed."""
import os
import random
import subprocess
import time

import pytest

from contactsim import AuthKeyError, auth

from conftest import BUILD

KEY = b"0123456789abcdef" * 4
CHANNEL = "CONTACTSIM_BODY_CMD"
PAYLOAD = b"contactsim test payload"
SEQ = 1764633600000000000  # 2025-12-02T00:00:00Z
SECOND = 10**9
VECTOR = ("43534731"                                                            # "CSG1"
          "0000b8e6e83c7d18"                                                    # seq, little-endian
          "6ebd12a8848bafd0607375328e5c7af72b67ee6d37b007ec580e53a8d1397246")  # HMAC-SHA256
TOOL = BUILD / "bin" / "contactsim-auth-sign"


def signed_at(seq, key=KEY, channel=CHANNEL, payload=PAYLOAD):
    return payload + auth.trailer(key, channel, payload, seq)


def test_trailer_matches_the_pinned_test_vector():
    assert auth.trailer(KEY, CHANNEL, PAYLOAD, SEQ).hex() == VECTOR
    assert auth.TRAILER_BYTES == 44


def test_signed_message_round_trips():
    signer = auth.Signer(KEY)
    msg = signer.sign(CHANNEL, PAYLOAD)
    assert msg[:len(PAYLOAD)] == PAYLOAD and len(msg) == len(PAYLOAD) + 44
    v = auth.verify(KEY, CHANNEL, msg)
    assert v.ok and v.payload_size == len(PAYLOAD) and v.seq == signer.last_seq, v
    assert auth.verify(KEY, CHANNEL, auth.Signer(KEY).sign(CHANNEL, b"")).ok


def test_wrong_key_or_channel_is_forged():
    for key, channel in ((b"x" * 32, CHANNEL), (KEY, "CONTACTSIM_SCENE_CMD")):
        v = auth.verify(key, channel, signed_at(SEQ))
        assert not v.ok and v.error.startswith("forged:"), v


def test_every_flipped_bit_is_refused():
    msg = signed_at(SEQ)
    magic = range(len(PAYLOAD), len(PAYLOAD) + 4)
    for i in range(len(msg)):
        for bit in range(8):
            bad = bytearray(msg)
            bad[i] ^= 1 << bit
            v = auth.verify(KEY, CHANNEL, bytes(bad))
            assert not v.ok, (i, bit)
            assert v.error.startswith("unsigned:" if i in magic else "forged:"), (i, v.error)


def test_missing_or_truncated_trailer_is_unsigned():
    assert auth.verify(KEY, CHANNEL, PAYLOAD).error.startswith("unsigned:")
    msg = signed_at(SEQ)
    for cut in range(1, 45):
        assert not auth.verify(KEY, CHANNEL, msg[:-cut]).ok, cut
    assert not auth.verify(KEY, CHANNEL, b"").ok


def test_unsigned_size_strips_only_a_trailer():
    assert auth.unsigned_size(signed_at(SEQ)) == len(PAYLOAD)
    assert auth.unsigned_size(PAYLOAD) == len(PAYLOAD)
    assert auth.unsigned_size(b"CSG1") == 4


def test_signer_seqs_increase_strictly_on_a_stuck_clock():
    signer = auth.Signer(KEY, clock=lambda: SEQ)
    seqs = [auth.verify(KEY, CHANNEL, signer.sign(CHANNEL, b"x")).seq for _ in range(5)]
    assert seqs == [SEQ, SEQ + 1, SEQ + 2, SEQ + 3, SEQ + 4]


def test_restarted_signer_continues_above_the_old_seq():
    window = auth.ReplayWindow()
    before = auth.Signer(KEY)
    for _ in range(100):
        before.sign(CHANNEL, b"x")
    assert window.accept("client", before.last_seq, before.last_seq)[0]
    after = auth.Signer(KEY)
    seq = auth.verify(KEY, CHANNEL, after.sign(CHANNEL, b"x")).seq
    assert seq > before.last_seq
    assert window.accept("client", seq, seq) == (True, "")


def test_stale_seqs_are_refused_in_the_past_and_the_future():
    w = auth.ReplayWindow()
    now = SEQ + 95_200_000_000
    assert w.accept("a", SEQ, now, 30.0) == (False, "stale: signed 95.2 s ago, window 30 s")
    assert w.accept("a", now + 31 * SECOND, now, 30.0) == (False, "stale: signed 31.0 s in the future, window 30 s")
    assert w.accept("a", now - 29 * SECOND, now, 30.0)[0]
    assert w.accept("a", now + 29 * SECOND, now, 30.0)[0]


def test_replayed_seq_is_refused_per_sender():
    w = auth.ReplayWindow()
    assert w.accept("a", SEQ, SEQ)[0]
    ok, why = w.accept("a", SEQ, SEQ)
    assert not ok and why.startswith("replayed:"), why
    assert w.accept("b", SEQ, SEQ)[0]


def test_reordered_within_64_are_accepted_once():
    w = auth.ReplayWindow()
    top = SEQ + 1000
    assert w.accept("a", top, SEQ)[0]
    for below in range(63, 0, -1):
        assert w.accept("a", top - below, SEQ)[0], below
        assert not w.accept("a", top - below, SEQ)[0], below
    ok, why = w.accept("a", top - 64, SEQ)
    assert not ok and "more than 64 below" in why


def test_window_slides_with_the_newest_seq():
    w = auth.ReplayWindow()
    assert w.accept("a", SEQ, SEQ)[0] and w.accept("a", SEQ + 10, SEQ)[0]
    assert not w.accept("a", SEQ, SEQ)[0]
    assert w.accept("a", SEQ + 5, SEQ)[0]
    assert w.accept("a", SEQ + 200, SEQ)[0]
    assert not w.accept("a", SEQ + 10, SEQ)[0]
    assert w.accept("a", SEQ + 199, SEQ)[0]


def test_sender_table_is_bounded_by_recency():
    w = auth.ReplayWindow(max_senders=3)
    for s in "abc":
        assert w.accept(s, SEQ, SEQ)[0]
    assert w.accept("a", SEQ + 1, SEQ)[0]   # a is now the most recent
    assert w.accept("d", SEQ, SEQ)[0]       # forgets b
    assert len(w) == 3
    assert not w.accept("a", SEQ + 1, SEQ)[0] and not w.accept("c", SEQ, SEQ)[0]
    assert w.accept("b", SEQ, SEQ)[0]
    big = auth.ReplayWindow()
    for i in range(5000):
        big.accept(str(i), SEQ, SEQ)
    assert len(big) == 4096


def test_key_file_trailing_whitespace_is_stripped(tmp_path):
    p = tmp_path / "key"
    p.write_bytes(KEY + b" \r\n\n")
    assert auth.load_key(p) == KEY


def test_short_or_missing_key_file_is_refused_with_its_name(tmp_path):
    p = tmp_path / "short.key"
    p.write_bytes(b"k" * 31 + b"\n")
    with pytest.raises(AuthKeyError, match=r"short\.key.*31 bytes.*openssl rand -hex 32"):
        auth.load_key(p)
    with pytest.raises(AuthKeyError, match=r'"/nonexistent/contactsim\.key": No such file'):
        auth.load_key("/nonexistent/contactsim.key")


def test_key_file_comes_from_the_argument_else_the_environment(monkeypatch):
    monkeypatch.setenv(auth.KEY_FILE_ENV, "/from/env")
    assert auth.resolve_key_file(None) == "/from/env"
    assert auth.resolve_key_file("/given") == "/given"
    assert auth.resolve_key_file("") is None
    monkeypatch.delenv(auth.KEY_FILE_ENV)
    assert auth.resolve_key_file(None) is None


def test_authenticator_drops_and_counts_what_fails():
    a = auth.Authenticator(KEY, clock=lambda: SEQ)
    assert a.unwrap("P_STATE", signed_at(SEQ, channel="P_STATE")) == PAYLOAD
    assert a.unwrap("P_STATE", signed_at(SEQ, channel="P_STATE")) is None      # replayed
    assert a.unwrap("P_STATUS", signed_at(SEQ, channel="P_STATUS")) == PAYLOAD  # its own window
    assert a.unwrap("P_STATE", PAYLOAD) is None
    assert a.failures == 2 and a.last_failure.startswith("P_STATE: unsigned:")


# Verifies that an observer (the viewer watching every client's RAY_CAST)
# takes another client's command by its mac alone: the same seq from two
# senders, or twice, is the server's to judge, while a forged or unsigned
# one is dropped.
def test_observed_commands_are_checked_by_their_mac_alone():
    a = auth.Authenticator(KEY, clock=lambda: SEQ)
    command = signed_at(SEQ, channel="P_RAY_CAST")
    assert a.observe("P_RAY_CAST", command) == PAYLOAD
    assert a.observe("P_RAY_CAST", command) == PAYLOAD
    assert a.observe("P_RAY_CAST", signed_at(SEQ, key=b"x" * 64, channel="P_RAY_CAST")) is None
    assert a.observe("P_BODY_CMD", command) is None
    assert a.observe("P_RAY_CAST", PAYLOAD) is None
    assert a.failures == 0


# ------------------------------------------------ agreement with the C++ library
def cpp_tool(args, data, key_file):
    if not TOOL.exists():
        pytest.skip("%s is not built (run `make`)" % TOOL)
    return subprocess.run([str(TOOL), "--key-file", str(key_file), *args], input=data, capture_output=True,
                          timeout=30)


@pytest.fixture
def key_file(tmp_path):
    p = tmp_path / "auth.key"
    p.write_bytes(KEY + b"\n")
    return p


def test_cpp_and_python_sign_byte_for_byte_alike(key_file):
    rng = random.Random(7)
    cases = [(CHANNEL, PAYLOAD, SEQ), ("X", b"", 1), ("CONTACTSIM_STATE", os.urandom(3000), 2**64 - 1)]
    cases += [("CH%d" % i, rng.randbytes(rng.randrange(200)), rng.getrandbits(64)) for i in range(5)]
    for channel, payload, seq in cases:
        out = cpp_tool(["--channel", channel, "--seq", str(seq)], payload, key_file)
        assert out.returncode == 0, out.stderr
        assert out.stdout == signed_at(seq, channel=channel, payload=payload), (channel, seq)


def test_python_verifies_cpp_and_cpp_verifies_python(key_file):
    out = cpp_tool(["--channel", "P_STATE"], PAYLOAD, key_file)
    v = auth.verify(KEY, "P_STATE", out.stdout)
    assert v.ok and v.payload_size == len(PAYLOAD), v
    assert abs(v.seq - time.time_ns()) < 30 * SECOND, "the C++ seq is the wall clock in ns"
    msg = auth.Signer(KEY).sign("P_BODY_CMD", PAYLOAD)
    ok = cpp_tool(["--channel", "P_BODY_CMD", "--verify"], msg, key_file)
    assert ok.returncode == 0 and ok.stdout.decode().startswith("ok %d " % len(PAYLOAD)), ok.stdout
    forged = cpp_tool(["--channel", "P_SCENE_CMD", "--verify"], msg, key_file)
    assert forged.returncode == 1 and forged.stdout.decode().startswith("forged:")


def test_cpp_tool_refuses_a_short_key(tmp_path):
    p = tmp_path / "short.key"
    p.write_bytes(b"short\n")
    out = cpp_tool(["--channel", "X"], b"", p)
    assert out.returncode == 2 and b"short.key" in out.stderr
