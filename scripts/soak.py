#!/usr/bin/env python3
"""Soak: a real server under random valid and invalid commands for a long
run, recorded with lcm-logger, then checked.

    .venv/bin/python scripts/soak.py [--steps 100000] [--build-dir build] [--seed 1] [--json]

Starts contactsim-server (free_run, a small scene with a few bodies and two
joints, its journal in a temporary folder) while lcm-logger records every
channel, and runs client threads, each with its own LCM instance and client
id, until the world has taken --steps steps:

* bodies: ADD (up to --max-bodies), REMOVE, SET_POSE, SET_VELOCITY,
  APPLY_FORCE, APPLY_IMPULSE, SET_MASS, SET_MATERIAL, joints ADD and
  REMOVE, with valid and invalid fields and unknown ids;
* world: SET_METHOD over every registered method (the list is read from
  the server's own refusal of an unknown one), SET_GRAVITY, SET_TIMESTEP,
  SET_MODE (free_run, realtime at 1000x, lockstep), PAUSE / STEP / RESUME,
  SNAPSHOT / RESTORE slots, REWIND, RESET followed by LOAD_SCENE, and
  invalid variants of each;
* controller: registers as a lockstep controller (wait policy), answers
  STATEs with small forces for a while, releases, again;
* garbage: malformed payloads on every channel (tests/python/lcm_wire.py).

Then it checks: the server never died and exits cleanly, no STATE in the
recording holds a NaN or infinity, the server's RSS at the end is within 5%
of its RSS after the warm-up (the first --warmup fraction of the steps), and
`contactsim-server --replay LOG` re-simulates the recording identically.
Exit status 0 when every check passes, 1 otherwise; --json prints the
summary as one JSON object.
"""
import argparse
import collections
import itertools
import json
import math
import random
import struct
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(REPO / "tests" / "python"))

import lcm  # noqa: E402

import contactsim  # noqa: E402
from contactsim import protocol, reply_t  # noqa: E402

import lcm_wire  # noqa: E402
from lcm_recorder import LcmRecorder  # noqa: E402
from server_process import ServerProcess  # noqa: E402

SCENE = """
gravity { z: -9.81 }
bodies { name: "ground" plane { normal { z: 1 } offset: 0 } }
bodies { name: "ball" sphere { radius: 0.1 } position { z: 0.5 } mass: 2 }
bodies { name: "crate" box { half_extents { x: 0.15 y: 0.1 z: 0.1 } } position { x: 0.6 z: 0.3 } density: 500 }
bodies { name: "pill" capsule { radius: 0.05 half_length: 0.1 } position { x: -0.6 z: 0.4 } }
bodies { name: "door" box { half_extents { x: 0.3 y: 0.02 z: 0.4 } } position { x: 0.3 y: 1 z: 0.45 } }
bodies { name: "bob" sphere { radius: 0.06 } position { x: -1 y: -1 z: 1 } }
joints { kind: "hinge" body_a: "door" anchor { y: 1 z: 0.45 } axis { z: 1 } limits { lower: -1 upper: 1 } }
joints { kind: "distance" body_a: "bob" anchor { x: -1 y: -1 z: 1.5 } }
"""
SLOTS = ("a", "b", "c")
# STATE and CONTACTS at rates of simulated time that lcm-logger keeps up with
# while the server runs free at thousands of steps a second: at the default
# 60 Hz it gets a STATE every 4 steps, and a recording that lost one command
# or reply in a burst cannot be replayed (see complete_recording).
CONFIG_OVERRIDES = {"state_rate_hz": "10", "contacts_rate_hz": "1"}
NAN, INF = math.nan, math.inf


class Tally:
    """Commands sent and replies by code, over every worker."""

    def __init__(self):
        self.lock = threading.Lock()
        self.sent = 0
        self.codes = collections.Counter()
        self.timeouts = 0
        self.by_op = collections.Counter()

    def add(self, op, code):
        with self.lock:
            self.sent += 1
            self.by_op[op] += 1
            if code is None:
                self.timeouts += 1
            else:
                self.codes[code] += 1


class Worker(threading.Thread):
    """Sends one random command after another until stopped."""

    def __init__(self, name, soak, seed):
        super().__init__(name=name, daemon=True)
        self.soak = soak
        self.rng = random.Random(seed)
        self.client = contactsim.Client(url=soak.url, prefix=soak.prefix, client_id="soak-%s" % name,
                                        timeout=soak.reply_timeout)
        self.error = None

    def send(self, op, fn):
        try:
            fn()
            code = reply_t.OK
        except contactsim.TimeoutError:
            code = None
        except contactsim.CommandError as e:
            code = e.code
        self.soak.tally.add(op, code)
        return code

    def run(self):
        try:
            while not self.soak.stop.is_set():
                self.one()
        except Exception as e:  # noqa: BLE001 - reported in the summary
            self.error = "%s: %r" % (self.name, e)
            self.soak.stop.set()
        finally:
            self.finish()
            self.client.close()

    def finish(self):
        pass

    def bodies(self):
        st = self.client.state()
        return sorted(st.bodies) if st is not None else []

    def near(self, body):
        """The body's latest BodyState, or None."""
        st = self.client.state()
        return st.bodies.get(body) if st is not None else None

    def vec(self, scale, n=3):
        return tuple(self.rng.uniform(-scale, scale) for _ in range(n))

    def bad_vec(self, n=3):
        v = list(self.vec(1.0, n))
        v[self.rng.randrange(n)] = self.rng.choice([NAN, INF, -INF])
        return tuple(v)


class BodyWorker(Worker):
    def one(self):
        c, rng = self.client, self.rng
        ids = self.bodies()
        dynamic = [i for i in ids if i > 1]  # id 1 is the ground plane in every scene this soak loads
        target = rng.choice(dynamic) if dynamic and rng.random() < 0.85 else rng.choice([0, 1, 999999, -5])
        valid = rng.random() < 0.8
        op = rng.randrange(11)
        if self.soak.wild:
            pos = (rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(0.2, 2.0))
        else:  # a cell of a coarse lattice in the air: a new pose seldom overlaps a body
            pos = (0.5 * rng.randrange(-3, 4), 0.5 * rng.randrange(-3, 4), 0.5 * rng.randrange(2, 5))
        if op == 0:
            if len(ids) >= self.soak.max_bodies:
                self.send("remove", lambda: c.remove_body(rng.choice(dynamic)))
                return
            shape = rng.randrange(4)
            size = rng.uniform(0.03, 0.15) if valid else rng.choice([-0.1, 0.0, NAN, INF])
            if shape == 0:
                self.send("add", lambda: c.add_sphere(size, position=pos, mass=rng.uniform(0.1, 5)))
            elif shape == 1:
                self.send("add", lambda: c.add_box((size, 0.08, 0.05), position=pos, density=rng.uniform(100, 3000)))
            elif shape == 2:
                self.send("add", lambda: c.add_capsule(0.04, size, position=pos, restitution=rng.uniform(0, 1)))
            else:
                pts = [(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)) for _ in range(8)]
                if not valid:
                    pts = pts[:rng.choice([1, 2])]
                self.send("add", lambda: c.add_convex(pts, position=pos, friction=rng.uniform(0, 1)))
        elif op == 1:
            if len(dynamic) > 3 or not valid:
                self.send("remove", lambda: c.remove_body(target if valid else 999999))
        elif op == 2:
            near = self.near(target)
            if self.soak.wild or near is None:
                p, q = pos, self.vec(1.0, 4)
            else:  # a nudge: a body teleported away from its joint's anchor is yanked back (and may blow up)
                p = tuple(float(v) for v in near.position + self.vec(0.05))
                q = tuple(float(v) for v in near.orientation + self.vec(0.05, 4))
            if not valid:
                p, q = rng.choice([(self.bad_vec(), q), (p, (0, 0, 0, 0)), (p, (NAN, 0, 0, 1)), (p, (1e-12, 0, 0, 0))])
            self.send("set_pose", lambda: c.set_pose(target, p, q))
        elif op == 3:
            self.send("set_velocity", lambda: c.set_velocity(target, self.vec(2.0) if valid else self.bad_vec(),
                                                             self.vec(3.0)))
        elif op == 4:
            self.send("apply_force", lambda: c.apply_force(target, self.vec(30.0) if valid else self.bad_vec(),
                                                           self.vec(1.0), rng.choice([0.0, 0.01, 0.1])
                                                           if valid else rng.choice([-1.0, NAN])))
        elif op == 5:
            near = self.near(target)
            point = tuple(float(v) for v in near.position + self.vec(0.1)) if near is not None else pos
            self.send("apply_impulse", lambda: c.apply_impulse(target, self.vec(0.5) if valid else self.bad_vec(),
                                                               rng.choice([None, point])))
        elif op == 6:
            m = rng.uniform(0.1, 5.0) if valid else rng.choice([-1.0, 0.0, NAN])
            self.send("set_mass", lambda: c.set_mass(target, mass=m) if rng.random() < 0.5 else
                      c.set_mass(target, density=m * 500))
        elif op == 7:
            self.send("set_material", lambda: c.set_material(
                target, restitution=rng.uniform(0, 1) if valid else rng.choice([-0.5, 1.5, NAN]),
                friction=rng.uniform(0, 1.5)))
        elif op == 8:
            if self.soak.max_joints == 0 and dynamic:
                # joints the server refuses (added joints can blow the physics up: --max-joints)
                a = rng.choice(dynamic)
                kind, b, extra = rng.choice([("ball", 999999, {}), ("ball", a, {}), ("hinge", None, {}),
                                             ("distance", None, dict(length=-1.0)),
                                             ("ball", None, dict(axis=(0, 0, 1)))])
                anchor = self.bad_vec() if rng.random() < 0.3 else (0.0, 0.0, 1.0)
                self.send("add_joint", lambda: c.add_joint(kind, a, b, anchor=anchor, **extra))
            elif len(self.soak.joints) >= self.soak.max_joints:
                jid = self.soak.joints.pop(0) if self.soak.joints else rng.randrange(1, 60)
                self.send("remove_joint", lambda: c.remove_joint(jid))
            elif len(dynamic) >= 2:
                a, b = rng.sample(dynamic, 2)
                kind = rng.choice(["ball", "distance", "hinge", "fixed"])
                other = rng.choice([b, None])
                st = c.state()
                if self.soak.wild or st is None or a not in st.bodies or (other is not None and other not in st.bodies):
                    anchor = pos
                else:  # between the two bodies, or just above a body held to the world
                    pa = st.bodies[a].position
                    pb = st.bodies[other].position if other is not None else pa + (0.0, 0.0, 0.3)
                    anchor = tuple(float(v) for v in (pa + pb) / 2)
                if not valid:
                    anchor = self.bad_vec()
                extra = dict(axis=self.vec(1.0)) if kind == "hinge" else {}
                if kind == "hinge" and rng.random() < 0.5:
                    extra["limits"] = (-0.5, 0.5) if valid else (0.5, -0.5)
                if kind == "distance" and self.soak.wild:
                    extra["length"] = rng.uniform(0.2, 1.0)
                self.send("add_joint", lambda: self.soak.joints.append(
                    c.add_joint(kind, a, other, anchor=anchor, **extra)))
        elif op == 9:
            self.send("remove_joint", lambda: c.remove_joint(rng.randrange(1, 60)))
        else:
            self.send("set_velocity", lambda: c.set_velocity(target, (0, 0, 0), (0, 0, 0)))


class WorldWorker(Worker):
    """Methods, world parameters, modes, snapshots, rewinds and resets."""

    def __init__(self, name, soak, seed):
        super().__init__(name, soak, seed)
        self.methods = soak.methods

    def one(self):
        time.sleep(self.rng.uniform(0.0, 0.02))  # the world changes less often than the bodies
        with self.soak.session:
            self.world_op()

    def world_op(self):
        c, rng = self.client, self.rng
        r = rng.random()
        valid = rng.random() < 0.8
        st = c.state()
        step = st.step if st is not None else 0
        if r < 0.25:
            name = rng.choice(self.methods) if valid else rng.choice(["nosuch", ""])
            params = {} if valid or rng.random() < 0.5 else {"nosuch_param": "1"}
            self.send("set_method", lambda: c.set_contact_method(name, **params))
        elif r < 0.32:
            g = (rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-12, -5)) if valid else self.bad_vec()
            self.send("set_gravity", lambda: c.set_gravity(g))
        elif r < 0.37:
            dt = rng.choice([1 / 240, 1 / 480, 1 / 120, 1 / 1000]) if valid else rng.choice([0.0, -1.0, 1.0, NAN])
            self.send("set_timestep", lambda: c.set_timestep(dt))
        elif r < 0.47:
            mode = rng.choice(["free_run", "free_run", "lockstep", "realtime"]) if valid else 9  # lockstep: no controller
            self.send("set_mode", lambda: c.set_mode(mode, real_time_factor=1000.0) if mode != 9 else
                      c._send("SCENE_CMD", _scene_op(contactsim.scene_cmd_t.SET_MODE, mode=9)))
        elif r < 0.55:
            self.send("pause", c.pause)
            for _ in range(rng.randrange(1, 4)):
                self.send("step", lambda: c.step(rng.randrange(1, 200) if valid else rng.choice([0, -3])))
            self.send("resume", c.resume)
        elif r < 0.65:
            self.send("snapshot", lambda: c.snapshot(rng.choice(SLOTS) if valid else "bad/slot"))
        elif r < 0.72:
            self.send("restore", lambda: c.restore(rng.choice(SLOTS) if valid else "nosuch"))
        elif r < 0.82:
            target = max(0, step - rng.randrange(0, 500)) if valid else rng.choice([-1, step + 10 ** 7])
            self.send("rewind", lambda: c.rewind(target))
        elif r < 0.85:
            self.send("reset", c.reset)
            self.send("load_scene", lambda: c.load_scene(self.soak.scene_path))
        elif r < 0.88:
            self.send("load_scene", lambda: c.load_scene(self.soak.scene_path if valid else "/nonexistent.pbtxt"))
        else:
            self.send("resume", c.resume)

    def finish(self):
        with self.soak.session:  # not in the middle of a controller's session
            try:
                self.client.set_mode("free_run")
            except contactsim.CommandError:
                pass


def _scene_op(op, **fields):
    m = contactsim.scene_cmd_t()
    m.op = op
    for k, v in fields.items():
        setattr(m, k, v)
    return m


class ControllerWorker(Worker):
    """A lockstep controller (wait policy) for a while, then none, again.

    A session holds soak.session: it switches to lockstep, runs, and
    switches back to free_run, while the world worker waits. Outside
    lockstep mode a controller's input races the free-running world and is
    refused when late, and a rewind or restore takes the world back behind
    the step contactsim.Controller last answered, after which it answers no
    STATE and a wait policy waits for ever.
    """

    def one(self):
        c, rng = self.client, self.rng

        def forces(state):
            out = {}
            for i in list(state.bodies)[1:4]:
                out[i] = ((rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(0, 5)), (0.0, 0.0, 0.0))
            if rng.random() < 0.01:  # an input the server refuses at its step (unknown body)
                out[999999] = (0.0, 0.0, 1.0)
            return out

        with self.soak.session:
            # lockstep first: a controller registered while the world runs free
            # answers a STATE the world has already left behind
            ctl = contactsim.Controller(c, forces, late="wait")
            self.send("set_mode", lambda: c.set_mode("lockstep"))
            self.send("register_controller", ctl.start)
            self.send("resume", c.resume)
            deadline = time.monotonic() + rng.uniform(0.5, 3.0)
            while time.monotonic() < deadline and not self.soak.stop.is_set():
                time.sleep(0.05)
            self.send("release_controller", ctl.stop)
            self.send("set_mode", lambda: c.set_mode("free_run"))
        ids = self.bodies()
        if ids and rng.random() < 0.3:  # an input from a released controller: refused
            c.send_input(c.state().step + 1, {ids[-1]: (0, 0, 1)})
        time.sleep(rng.uniform(0.2, 1.0))


class GarbageWorker(Worker):
    """Malformed payloads on every channel, now and then."""

    def __init__(self, name, soak, seed):
        super().__init__(name, soak, seed)
        self.garbage = lcm_wire.Garbage(seed=seed, client_id=self.client.client_id + "-g",
                                        request_ids=itertools.count(1))
        self.lc = lcm.LCM(soak.url)

    def one(self):
        # only payloads no decoder reads as a command: a mutant that still
        # decodes is a command from a sender id that may hold a NUL, whose
        # reply (under the id cut at the NUL) neither lcm-logger's reader nor
        # a replay can pair with it; the workers send well-formed invalid
        # commands, and test_garbage.py the rest
        while True:
            channel, payload, _ = self.garbage.one(self.rng.choice(lcm_wire.Garbage.KINDS))
            try:
                lcm_wire.lenient_decode(lcm_wire.CHANNEL_TYPES[channel], payload)
            except lcm_wire.Malformed:
                break
        if len(payload) > 60000:
            payload = payload[:60000]
        self.lc.publish("%s_%s" % (self.soak.prefix, channel), payload)
        self.soak.tally.add("garbage", -1)
        time.sleep(self.rng.uniform(0.005, 0.05))


class StepCounter:
    """Counts the steps the world takes, from the STATE headers: forward
    progress only (a reset, restore or rewind starts the count anew from the
    step the world is then at)."""

    def __init__(self, url, channel):
        self.lc = lcm.LCM(url)
        self.total = 0
        self.last = None
        self.states = 0
        sub = self.lc.subscribe(channel, self._on_state)
        sub.set_queue_capacity(100000)
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def _on_state(self, channel, data):
        _, step = struct.unpack_from(">dq", data, 8)
        self.states += 1
        if self.last is not None and step > self.last:
            self.total += step - self.last
        self.last = step

    def _run(self):
        while not self.stop.is_set():
            self.lc.handle_timeout(50)

    def close(self):
        self.stop.set()
        self.thread.join(2.0)


def registered_methods(client):
    """The contact methods the server knows, from its refusal of an unknown one."""
    try:
        client.set_contact_method("soak-no-such-method")
    except contactsim.CommandError as e:
        known = e.message.split("(known:", 1)[1].rsplit(")", 1)[0]
        return [m.strip() for m in known.split(",") if m.strip()]
    raise RuntimeError("the server accepted an unknown contact method")


def complete_recording(log_path, prefix, clients):
    """(commands logged without their reply, or steps whose STATE shows
    applied lockstep inputs without an INPUT in the log; replies logged
    without their command), counting only the well-behaved clients' (garbage
    has no reliable sender): both 0 when lcm-logger lost no command, input
    or reply on UDP, which a replay needs. A good input gets no reply.
    A command lost together with its reply shows as a gap in its client's
    request ids, which count up by one per command or input (a resend keeps
    its id); each missing id counts as unanswered."""
    commands, replies, input_steps, digest_steps = set(), set(), set(), set()
    for e in lcm.EventLog(str(log_path), "r"):
        ch = e.channel[len(prefix) + 1:]
        if ch in protocol.INCOMING:
            try:
                m = protocol.message_class(ch).decode(e.data)
            except Exception:  # noqa: BLE001 - garbage
                continue
            unreplied = not protocol.CHANNELS[ch].replied  # a lockstep input
            if m.client_id in clients:
                commands.add((unreplied, m.client_id, m.request_id))
                if unreplied:
                    input_steps.add(m.step)
        elif ch == "REPLY":
            r = contactsim.reply_t.decode(e.data)
            if r.client_id in clients:
                replies.add((r.client_id, r.request_id))
        elif ch == "STATE":
            m = contactsim.state_t.decode(e.data)
            if m.input_digest != 0:  # inputs were applied in this step: one must be in the log
                digest_steps.add(m.step)
    sent = {(c, r) for _, c, r in commands}
    unanswered = len({(c, r) for is_input, c, r in commands if not is_input} - replies)
    return unanswered + request_id_gaps(sent | replies) + len(digest_steps - input_steps), len(replies - sent)


def request_id_gaps(requests):
    """Request ids missing between each client's first and last in
    ``requests`` ((client id, request id) pairs)."""
    ids = {}
    for client, rid in requests:
        ids.setdefault(client, set()).add(rid)
    return sum(max(r) - min(r) + 1 - len(r) for r in ids.values())


def check_states(log_path, prefix):
    """(STATEs in the recording, those with a NaN or infinity, first bad step)."""
    channel = protocol.channel(prefix, "STATE")
    n = bad = 0
    first = None
    for e in lcm.EventLog(str(log_path), "r"):
        if e.channel != channel:
            continue
        m = contactsim.state_t.decode(e.data)
        n += 1
        values = [m.time, m.kinetic_energy, m.potential_energy]
        for b in m.bodies:
            values += list(b.position) + list(b.orientation) + list(b.linear_velocity) + list(b.angular_velocity)
        if not all(math.isfinite(v) for v in values):
            bad += 1
            first = m.step if first is None else first
    return n, bad, first


class Soak:
    def __init__(self, args):
        self.args = args
        self.tally = Tally()
        self.stop = threading.Event()
        self.max_bodies = args.max_bodies
        self.max_joints = args.max_joints if not args.wild else 10 ** 6
        self.wild = args.wild
        # a controller session and the world worker's mode, rewind, restore,
        # reset and load commands exclude each other (see ControllerWorker)
        self.session = threading.Lock()
        self.joints = []  # ids of the joints the workers added (some may be gone with their bodies)
        self.reply_timeout = args.reply_timeout

    def run(self):
        a = self.args
        work = Path(a.keep) if a.keep else Path(tempfile.mkdtemp(prefix="contactsim-soak-"))
        work.mkdir(parents=True, exist_ok=True)
        journal = work / "journal"
        log_path = work / "soak.lcmlog"
        self.scene_path = str(work / "scene.pbtxt")
        srv = ServerProcess(a.build_dir, scene_text=SCENE, args=["--journal", str(journal)], tag="SOAK",
                            workdir=work, timeout=a.reply_timeout, config_overrides=CONFIG_OVERRIDES)
        self.url, self.prefix = srv.url, srv.prefix
        summary = dict(steps_target=a.steps, seed=a.seed, workdir=str(work))
        rss = []  # (steps, KiB)
        t0 = time.monotonic()
        with LcmRecorder(self.url, self.prefix + "_.*", log_path):
            srv.start()
            self.methods = registered_methods(srv.client)
            summary["methods"] = self.methods
            counter = StepCounter(self.url, srv.client.channels["STATE"])
            workers = [BodyWorker("bodies", self, a.seed * 10 + 1), BodyWorker("bodies2", self, a.seed * 10 + 2),
                       WorldWorker("world", self, a.seed * 10 + 3), ControllerWorker("controller", self, a.seed * 10 + 4)]
            if a.garbage:
                workers.append(GarbageWorker("garbage", self, a.seed * 10 + 5))
            srv.client.resume()
            for w in workers:
                w.start()
            last_print = 0.0
            while counter.total < a.steps and not self.stop.is_set():
                time.sleep(0.2)
                if not srv.alive():
                    self.stop.set()
                    break
                rss.append((counter.total, srv.rss_kib()))
                if a.max_seconds and time.monotonic() - t0 > a.max_seconds:
                    break
                if not a.json and time.monotonic() - last_print > 5.0:
                    last_print = time.monotonic()
                    print("  %7d steps  %6d commands  RSS %d KiB" % (counter.total, self.tally.sent, rss[-1][1]),
                          file=sys.stderr, flush=True)
            self.stop.set()
            for w in workers:
                w.join(30.0)
            alive = srv.alive()
            if alive:
                try:
                    srv.client.set_mode("free_run")
                    srv.client.pause()
                except contactsim.CommandError:
                    pass
            counter.close()
        wall = time.monotonic() - t0
        end_rss = srv.rss_kib() if alive else None
        rc = srv.stop()
        summary.update(steps=counter.total, states_seen=counter.states, wall_s=round(wall, 1),
                       steps_per_s=round(counter.total / wall, 1) if wall > 0 else 0,
                       commands_sent=self.tally.sent, replies_by_code={
                           contactsim.errors.CODE_NAMES.get(k, str(k)): v for k, v in sorted(self.tally.codes.items())
                           if k >= 0},
                       garbage_sent=self.tally.codes.get(-1, 0), reply_timeouts=self.tally.timeouts,
                       accepted=self.tally.codes.get(reply_t.OK, 0),
                       rejected=sum(v for k, v in self.tally.codes.items() if k > 0),
                       commands_by_op=dict(sorted(self.tally.by_op.items())),
                       worker_errors=[w.error for w in workers if w.error],
                       server_alive_at_end=alive, server_exit=rc)
        warm = [kib for steps, kib in rss if kib is not None and steps >= a.warmup * counter.total]
        if warm:
            summary.update(rss_start_kib=rss[0][1], rss_after_warmup_kib=warm[0], rss_end_kib=end_rss or warm[-1],
                           rss_max_kib=max(k for _, k in rss if k is not None))
            summary["rss_growth_after_warmup"] = round((summary["rss_end_kib"] - warm[0]) / warm[0], 4)
            pts = [(st, k) for st, k in rss if k is not None]
            summary["rss_series"] = pts[::max(1, len(pts) // 20)] + pts[-1:]  # (steps, KiB), for a trend
        n, bad, first = check_states(log_path, self.prefix)
        summary.update(states_recorded=n, states_with_nan=bad, first_nan_step=first)
        unanswered, orphans = complete_recording(log_path, self.prefix,
                                                 {w.client.client_id for w in workers} | {srv.client.client_id})
        # informative: a replay that diverges on an incomplete recording says
        # more about lcm-logger than about the server
        summary.update(recording_commands_without_reply=unanswered, recording_replies_without_command=orphans,
                       recording_complete=unanswered == 0 and orphans == 0)
        out = subprocess.run([str(srv.binary), "--config", str(srv.config), "--scene", str(srv.scene),
                              "--prefix", self.prefix, "--replay", str(log_path)],
                             capture_output=True, text=True, timeout=a.replay_timeout)
        summary.update(replay_exit=out.returncode, replay=(out.stdout.strip().splitlines() or [""])[0],
                       replay_stderr_tail=out.stderr[-1500:] if out.returncode else "")
        checks = {
            "server never died and exited 0": alive and rc == 0,
            "steps reached": counter.total >= a.steps,
            "no worker failed": not summary["worker_errors"],
            "no NaN or infinity in any STATE": n > 0 and bad == 0,
            "RSS growth after warm-up < 5%": bool(warm) and summary["rss_growth_after_warmup"] < 0.05,
            "replay identical": out.returncode == 0,
        }
        summary["checks"] = checks
        summary["ok"] = all(checks.values())
        summary["server_log_tail"] = "" if summary["ok"] else srv.log_tail(3000)
        return summary


def print_summary(s):
    print("soak: %d steps in %.1f s (%.0f steps/s), seed %d, methods %s" % (
        s["steps"], s["wall_s"], s["steps_per_s"], s["seed"], ", ".join(s["methods"])))
    print("  commands sent %d: accepted %d, rejected %d %s, no reply %d; garbage payloads %d" % (
        s["commands_sent"], s["accepted"], s["rejected"], s["replies_by_code"], s["reply_timeouts"],
        s["garbage_sent"]))
    if "rss_start_kib" in s:
        print("  RSS KiB: start %d, after warm-up %d, end %d, max %d (growth after warm-up %+.2f%%)" % (
            s["rss_start_kib"], s["rss_after_warmup_kib"], s["rss_end_kib"], s["rss_max_kib"],
            100 * s["rss_growth_after_warmup"]))
    print("  STATEs recorded %d, with NaN/inf %d" % (s["states_recorded"], s["states_with_nan"]))
    print("  recording %s (%d commands or lockstep steps without a reply or input, %d replies without a command)" % (
        "complete" if s["recording_complete"] else "INCOMPLETE: lcm-logger lost messages",
        s["recording_commands_without_reply"], s["recording_replies_without_command"]))
    print("  replay: exit %d, %s" % (s["replay_exit"], s["replay"]))
    for name, ok in s["checks"].items():
        print("  [%s] %s" % ("ok" if ok else "FAILED", name))
    if s["worker_errors"]:
        print("  worker errors: %s" % s["worker_errors"])
    if not s["ok"]:
        print("  files kept in %s" % s["workdir"])
        if s["replay_stderr_tail"]:
            print(s["replay_stderr_tail"])
        print(s["server_log_tail"])


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--steps", type=int, default=100000, help="steps the world must take (default 100000)")
    p.add_argument("--build-dir", default=None, help="build folder (default $CONTACTSIM_BUILD_DIR or build)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--max-bodies", type=int, default=24, help="bodies the workers add up to")
    p.add_argument("--max-joints", type=int, default=0,
                   help="joints the workers add and keep at most (default 0: only joints the server refuses, and "
                        "removals; with joints added among random bodies the physics can blow up to NaN)")
    p.add_argument("--warmup", type=float, default=0.5,
                   help="fraction of the steps before the RSS reference (default 0.5: RSS rises for the first tens of "
                        "thousands of steps, then stays flat)")
    p.add_argument("--wild", action="store_true",
                   help="poses anywhere (overlapping bodies) and joints without limit: valid, but the physics may "
                        "blow up, so expect NaN")
    p.add_argument("--no-garbage", dest="garbage", action="store_false", help="send no malformed payloads")
    p.add_argument("--reply-timeout", type=float, default=30.0, help="s a worker waits for a reply")
    p.add_argument("--replay-timeout", type=float, default=1800.0)
    p.add_argument("--max-seconds", type=float, default=0.0, help="stop after this many seconds (0: no limit)")
    p.add_argument("--keep", default=None, help="folder for the recording, journal and logs (default: a temp folder)")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    args = p.parse_args(argv)
    summary = Soak(args).run()
    if args.json:
        print(json.dumps(summary))
    else:
        print_summary(summary)
    return 0 if summary["ok"] else 1


if __name__ == "__main__":
    sys.exit(main())
