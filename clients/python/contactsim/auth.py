"""Signed LCM messages (docs/protocol.md, "Authentication").

A signed message is the ordinary LCM encoding followed by a 44-byte trailer::

    payload | b"CSG1" | seq (u64, little-endian) | mac (32 bytes)
    mac = HMAC-SHA256(key, channel || 0x00 || payload || b"CSG1" || seq_le)

``seq`` is the sender's wall clock in ns since the Unix epoch, made strictly
increasing per sender, so receivers refuse stale and replayed messages. The
same format as protocol/include/contactsim/signature.h (the C++ server's
and client's); both test suites pin
one test vector.
"""
import collections
import hashlib
import hmac
import os
import struct
import threading
import time

from .errors import AuthKeyError

MAGIC = b"CSG1"
MAC_BYTES = 32
TRAILER_BYTES = len(MAGIC) + 8 + MAC_BYTES  # 44
MIN_KEY_BYTES = 32
DEFAULT_WINDOW_S = 30.0
REPLAY_WINDOW_SLOTS = 64
DEFAULT_MAX_SENDERS = 4096
KEY_FILE_ENV = "CONTACTSIM_AUTH_KEY_FILE"
_SEQ = struct.Struct("<Q")


def load_key(path):
    """The key in ``path``: its bytes with trailing whitespace removed."""
    try:
        with open(path, "rb") as f:
            key = f.read().rstrip(b" \t\r\n\v\f")
    except OSError as e:
        raise AuthKeyError('cannot read auth key file "%s": %s' % (path, e.strerror or e)) from None
    if len(key) < MIN_KEY_BYTES:
        raise AuthKeyError('auth key file "%s" holds a key of %d bytes; at least %d are needed '
                           "(make one with: openssl rand -hex 32 > %s)" % (path, len(key), MIN_KEY_BYTES, path))
    return key


def resolve_key_file(path=None):
    """``path`` when given (None: $CONTACTSIM_AUTH_KEY_FILE); None or "" means no signing."""
    if path is None:
        path = os.environ.get(KEY_FILE_ENV)
    return os.fspath(path) if path else None


def trailer(key, channel, payload, seq):
    """The 44-byte trailer of ``payload`` on ``channel`` with a given seq."""
    head = MAGIC + _SEQ.pack(seq)
    mac = hmac.new(key, channel.encode() + b"\0" + bytes(payload) + head, hashlib.sha256).digest()
    return head + mac


class Signer:
    """Signs the messages of one sender; thread-safe. ``clock`` gives ns since the epoch."""

    def __init__(self, key, clock=time.time_ns):
        self._key = bytes(key)
        self._clock = clock
        self._lock = threading.Lock()
        self.last_seq = 0

    def sign(self, channel, payload):
        """payload followed by its trailer, seq = max(now, last seq + 1)."""
        with self._lock:
            self.last_seq = seq = max(self._clock(), self.last_seq + 1)
        return bytes(payload) + trailer(self._key, channel, payload, seq)


Verified = collections.namedtuple("Verified", "ok payload_size seq error")


def has_trailer(data):
    """True when ``data`` ends with something shaped like a trailer (says nothing of the mac)."""
    return len(data) >= TRAILER_BYTES and data[-TRAILER_BYTES:-TRAILER_BYTES + len(MAGIC)] == MAGIC


def unsigned_size(data):
    """The payload size with a trailer (if any) stripped: what a receiver without a key decodes."""
    return len(data) - TRAILER_BYTES if has_trailer(data) else len(data)


def verify(key, channel, data):
    """Checks the trailer and the mac (constant time). ``error`` starts with
    "unsigned:" or "forged:"; freshness and replay are ReplayWindow's."""
    if not has_trailer(data):
        return Verified(False, 0, 0, 'unsigned: no signature trailer ("CSG1" at 44 bytes from the end of '
                        "%d bytes)" % len(data))
    n = len(data) - TRAILER_BYTES
    seq = _SEQ.unpack_from(data, n + len(MAGIC))[0]
    if not hmac.compare_digest(trailer(key, channel, data[:n], seq), bytes(data[n:])):
        return Verified(False, 0, 0, "forged: the signature does not match the key and the channel %s" % channel)
    return Verified(True, n, seq, "")


def check_freshness(seq, now_ns, window_s):
    """None when |seq - now| <= window_s, else e.g. "signed 95.2 s ago, window 30 s"."""
    age = (now_ns - seq) * 1e-9
    if abs(age) <= window_s:
        return None
    return "signed %.1f s %s, window %g s" % (abs(age), "ago" if age > 0 else "in the future", window_s)


class ReplayWindow:
    """Per-sender anti-replay state as IPsec's (RFC 4303 section 3.4.3): the
    highest seq and a 64-wide bitmap below it. At most ``max_senders``,
    forgetting the least recently seen. Thread-safe."""

    def __init__(self, max_senders=DEFAULT_MAX_SENDERS):
        self.max_senders = max(1, max_senders)
        self._entries = collections.OrderedDict()  # sender -> [highest, seen bits]; most recent last
        self._lock = threading.Lock()

    def __len__(self):
        return len(self._entries)

    def accept(self, sender, seq, now_ns, window_s=DEFAULT_WINDOW_S):
        """(True, "") when accepted (and remembered), else (False, "stale: ..." or "replayed: ...")."""
        stale = check_freshness(seq, now_ns, window_s)
        if stale:
            return False, "stale: " + stale
        with self._lock:
            entry = self._entries.get(sender)
            if entry is None:
                if len(self._entries) >= self.max_senders:
                    self._entries.popitem(last=False)
                self._entries[sender] = [seq, 1]
                return True, ""
            self._entries.move_to_end(sender)
            return self._accept_in(entry, seq)

    @staticmethod
    def _accept_in(entry, seq):
        highest, seen = entry
        if seq > highest:
            shift = seq - highest
            entry[:] = [seq, 1 if shift >= REPLAY_WINDOW_SLOTS else ((seen << shift) | 1) & (2**64 - 1)]
            return True, ""
        below = highest - seq
        if below >= REPLAY_WINDOW_SLOTS:
            return False, "replayed: seq %d is more than %d below the newest seen (%d)" % (
                seq, REPLAY_WINDOW_SLOTS, highest)
        if seen >> below & 1:
            return False, "replayed: seq %d was seen before" % seq
        entry[1] = seen | 1 << below
        return True, ""


class Authenticator:
    """A client's side of it: signs what it publishes and checks what the
    server publishes (mac, freshness, replay keyed by channel), counting and
    explaining what it drops. Thread-safe."""

    def __init__(self, key, window_s=DEFAULT_WINDOW_S, clock=time.time_ns):
        self._key = bytes(key)
        self.window_s = window_s
        self._clock = clock
        self.signer = Signer(self._key, clock)
        self._replay = ReplayWindow()
        self._lock = threading.Lock()
        self.failures = 0
        self.last_failure = ""

    @classmethod
    def from_key_file(cls, path=None, window_s=DEFAULT_WINDOW_S):
        """An Authenticator for the key in ``path`` (None: $CONTACTSIM_AUTH_KEY_FILE), or
        None when neither names a file. Raises AuthKeyError."""
        path = resolve_key_file(path)
        return cls(load_key(path), window_s) if path else None

    def sign(self, channel, payload):
        return self.signer.sign(channel, payload)

    def observe(self, channel, data):
        """The payload of another client's command that carries this key's
        mac, or None. Its freshness and replay are the server's to judge:
        every sender counts its own seq."""
        v = verify(self._key, channel, data)
        return bytes(data[:v.payload_size]) if v.ok else None

    def unwrap(self, channel, data):
        """The payload of a verified message from the server, or None (counted)."""
        v = verify(self._key, channel, data)
        ok, why = (v.ok, v.error)
        if ok:
            ok, why = self._replay.accept(channel, v.seq, self._clock(), self.window_s)
        if ok:
            return bytes(data[:v.payload_size])
        with self._lock:
            self.failures += 1
            self.last_failure = "%s: %s" % (channel, why)
        return None


__all__ = ["AuthKeyError", "Authenticator", "ReplayWindow", "Signer", "Verified", "check_freshness",
           "has_trailer", "load_key", "resolve_key_file", "trailer", "unsigned_size", "verify",
           "DEFAULT_WINDOW_S", "KEY_FILE_ENV", "MAGIC", "MIN_KEY_BYTES", "TRAILER_BYTES"]
