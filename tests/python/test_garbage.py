"""Garbage on every command channel of a real server: random bytes, truncated,
bit-flipped and overwritten messages, string lengths of 0, -1 and huge,
negative and huge array counts, over-long payloads, one type's message on
another type's channel and spliced messages, made by a seeded RNG from a
valid message of every op (lcm_wire.py), and the SCENE_CMD payload
that once made the server throw std::length_error.

Payloads that still decode to a command that would change the paused world
(an ADD, a RESET, a STEP, a pose for a body that exists, ...) are left out:
they are well-formed commands, not garbage. Every other payload must get
exactly one reply and change nothing: afterwards the server runs, its STATE
(hash, clock and every body, bit for bit) is the one from before, and a
normal command gets the next body id.

CONTACTSIM_GARBAGE_COUNT (default 3000) sets the number of payloads,
CONTACTSIM_GARBAGE_SEED the seed.
"""
import collections
import os
import threading
import time

import lcm
import pytest

import contactsim
from contactsim import reply_t

from conftest import current_state

import lcm_wire  # noqa: E402

COUNT = int(os.environ.get("CONTACTSIM_GARBAGE_COUNT", "3000"))
SEED = int(os.environ.get("CONTACTSIM_GARBAGE_SEED", "20261201"))
IN_FLIGHT_BYTES = 1 << 20   # unanswered bytes before the test waits: well inside the 8 MiB receive buffer
IN_FLIGHT_COUNT = 200
REPLY_WAIT = 20.0           # s for the replies of one window; a crashed server is seen sooner

GRAVITY = (0.0, 0.0, -9.81)
SCENE = """
gravity { z: -9.81 }
bodies { name: "ground" plane { normal { z: 1 } offset: 0 } }
bodies { name: "ball" sphere { radius: 0.1 } position { z: 0.5 } linear_velocity { x: 0.3 } mass: 2 }
bodies { name: "crate" box { half_extents { x: 0.1 y: 0.2 z: 0.05 } } position { x: 1 z: 0.3 }
         orientation { w: 0.9 x: 0.1 y: 0.3 } angular_velocity { x: 2 } density: 500 }
bodies { name: "door" box { half_extents { x: 0.4 y: 0.02 z: 0.8 } } position { x: -2 z: 0.85 } }
bodies { name: "bob" capsule { radius: 0.05 half_length: 0.1 } position { x: 3 z: 2 } }
joints { kind: "hinge" body_a: "door" anchor { x: -2.4 z: 0.85 } axis { z: 1 } limits { lower: -1 upper: 1 } }
joints { kind: "distance" body_a: "bob" anchor { x: 3 z: 3 } }
"""
N_BODIES, N_JOINTS = 5, 2


class ReplyCounter:
    """Counts the replies on the REPLY channel that are not the test client's."""

    def __init__(self, url, channel, own_id):
        self.lc = lcm.LCM(url)
        self.own_id = own_id
        self.codes = collections.Counter()
        self.count = 0
        self.lock = threading.Lock()
        self.sub = self.lc.subscribe(channel, self._on_reply)
        self.sub.set_queue_capacity(100000)
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _on_reply(self, channel, data):
        r = reply_t.decode(data)
        if r.client_id == self.own_id:
            return
        with self.lock:
            self.count += 1
            self.codes[r.code] += 1

    def _run(self):
        while not self.stop.is_set():
            self.lc.handle_timeout(20)

    def close(self):
        self.stop.set()
        self.thread.join(2.0)


def test_garbage_on_every_channel_crashes_nothing_and_changes_nothing(launch, tmp_path):
    scene = tmp_path / "garbage-scene.pbtxt"
    scene.write_text(SCENE)
    server = launch(scene=scene)
    client = server.client
    client.step(3)
    before = current_state(client, GRAVITY)
    assert len(before.bodies) == N_BODIES

    world = dict(bodies=set(before.bodies), joints=set(range(1, N_JOINTS + 1)), slots=set())
    gen = lcm_wire.Garbage(seed=SEED)
    corpus = gen.corpus(COUNT, world)
    kinds = collections.Counter(channel for channel, _, _ in corpus)
    assert set(kinds) == set(lcm_wire.CHANNEL_TYPES)

    counter = ReplyCounter(server.url, client.channels["REPLY"], client.client_id)
    pub = lcm.LCM(server.url)
    sent = sent_bytes = 0
    window = []   # (channel, payload, description) not yet answered
    try:
        for channel, payload, what in corpus:
            pub.publish(client.channels[channel], payload)
            sent += 1
            sent_bytes += len(payload)
            window.append((channel, payload, what))
            if sum(len(p) for _, p, _ in window) > IN_FLIGHT_BYTES or len(window) >= IN_FLIGHT_COUNT:
                _wait_for_replies(server, counter, sent, window)
                window = []
        _wait_for_replies(server, counter, sent, window)
        time.sleep(0.2)  # and no extra replies
    finally:
        counter.close()

    codes = {contactsim.errors.CODE_NAMES.get(k, k): v for k, v in sorted(counter.codes.items())}
    print("\ngarbage: %d payloads (%d bytes; %d well-formed world-changing mutants left out), per channel %s; "
          "replies %d by code %s" % (sent, sent_bytes, gen.left_out, dict(kinds), counter.count, codes))
    assert server.proc.poll() is None, "server died:\n" + server.log()
    assert counter.count == sent, "%d payloads, %d replies (%s)" % (sent, counter.count, codes)
    assert counter.codes[reply_t.DECODE_ERROR] > 0

    after = current_state(client, GRAVITY)
    assert after.state_hash == before.state_hash
    assert after == before, "garbage changed the world"
    # a normal command still works and no body id was used up
    assert client.add_sphere(0.05, position=(5, 5, 1)) == max(before.bodies) + 1
    assert client.step(1).step == before.step + 1
    assert client.wait_for_status(lambda s: s.commands_rejected >= sent - counter.codes[reply_t.OK],
                                  timeout=5.0) is not None


def _wait_for_replies(server, counter, sent, window):
    deadline = time.monotonic() + REPLY_WAIT
    while counter.count < sent and time.monotonic() < deadline:
        if server.proc.poll() is not None:
            break
        time.sleep(0.005)
    if server.proc.poll() is not None:
        shown = "\n".join("  %s %s: %s" % (c, what, p[:96].hex()) for c, p, what in window[-20:])
        pytest.fail("server died (exit %s) within these payloads (the last 20 of the window):\n%s\nlog:\n%s" % (
            server.proc.returncode, shown, server.log()))
