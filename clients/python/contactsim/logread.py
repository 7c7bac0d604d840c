"""Reads an LCM log of a contactsim run (``lcm-logger`` output) into numpy arrays.

    from contactsim.logread import read_log
    log = read_log("run.lcmlog")
    e = log.kinetic_energy + log.potential_energy       # J, per STATE
    z = log.position[:, log.body_index[ball], 2]         # m, NaN while absent

One function, ``read_log``; ``python -m contactsim.plot`` draws from it.
"""
import os
from types import SimpleNamespace

import lcm
import numpy as np

from . import contacts_t, protocol, state_t, status_t
from .logread_joints import JointTrajectories
from .state import MODE_NAMES


def _detect_prefix(path):
    """The prefix of the first ``<P>_STATE`` channel in the log (not a
    channel whose own name ends in _STATE, as JOINT_STATE does)."""
    suffix = protocol.channel("", "STATE")
    longer = tuple(protocol.channel("", n) for n in protocol.CHANNELS if n != "STATE" and n.endswith("_STATE"))
    log = lcm.EventLog(path, "r")
    try:
        for event in log:
            if event.channel.endswith(suffix) and not event.channel.endswith(longer):
                return event.channel[:-len(suffix)]
    finally:
        log.close()
    return "CONTACTSIM"


def _progress(total, enabled):
    """A tqdm bar over ``total`` bytes, or a stand-in that does nothing."""
    if enabled:
        try:
            from tqdm import tqdm
            return tqdm(total=total, unit="B", unit_scale=True, desc="reading log", leave=False)
        except ImportError:  # the bar is a nicety, never a reason to fail
            pass
    return SimpleNamespace(update=lambda n: None, close=lambda: None)


def _decode_state(event):
    """A logged STATE, or a ValueError that says why not: a STATE recorded by
    a contactsim whose state_t had another layout (its fingerprint, the
    first 8 bytes, differs) cannot be read by this one."""
    try:
        return state_t.decode(event.data)
    except ValueError:
        fingerprint = bytes(event.data[:8])
        if fingerprint != state_t._get_packed_fingerprint():
            raise ValueError(
                "the STATE on %s at log event %d is not this contactsim's state_t (fingerprint %s, expected %s): "
                "the log was recorded by another version of contactsim; read it with that version"
                % (event.channel, event.eventnum, fingerprint.hex(), state_t._get_packed_fingerprint().hex())) from None
        raise ValueError("the STATE on %s at log event %d does not decode (truncated or corrupt)"
                         % (event.channel, event.eventnum)) from None


def _stack_bodies(ids_per_state, rows_per_state):
    """(N, B, 13) array over the union of body ids, NaN where a body is absent
    from a STATE (added later or removed earlier)."""
    body_ids = np.unique(np.concatenate(ids_per_state)) if ids_per_state else np.zeros(0, np.int64)
    column = {int(b): i for i, b in enumerate(body_ids)}
    out = np.full((len(rows_per_state), len(body_ids), 13), np.nan)
    for n, (ids, rows) in enumerate(zip(ids_per_state, rows_per_state)):
        if len(ids):
            out[n, [column[int(b)] for b in ids]] = rows
    return body_ids.astype(np.int64), column, out


def read_log(path, prefix=None, progress=False):
    """Reads the STATE, CONTACTS and STATUS messages of one server from an
    LCM event log (``lcm.EventLog``) into numpy arrays, in log order.

    ``prefix`` is the channel prefix (default: that of the first ``*_STATE``
    channel in the log); ``progress`` shows a progress bar (tqdm) while
    reading. Returns a namespace with:

    * per STATE message (N of them): ``time`` (s, simulated), ``step``,
      ``log_time`` (s since the first event of the log, wall clock),
      ``state_hash`` and ``input_digest`` (uint64), ``kinetic_energy`` and
      ``potential_energy`` (J, of the dynamic bodies);
    * ``body_ids`` (B,) every body id seen, ascending; ``body_index`` maps an
      id to its column; ``position`` (N, B, 3, m), ``orientation`` (N, B, 4,
      w x y z), ``linear_velocity`` (N, B, 3, m/s), ``angular_velocity``
      (N, B, 3, rad/s), world frame, NaN where a body did not exist;
    * ``contacts``: per CONTACTS message (M) ``time``, ``step``, ``count``,
      ``max_depth`` (m, 0 without contacts), ``total_normal_force`` (N; an
      impulse method's N s over the step divided by dt) and ``value_kind``
      ("impulse" / "force"); per contact point (K) ``frame`` (index of its
      message), ``body_a``, ``body_b``, ``point`` (K, 3), ``normal`` (K, 3),
      ``depth``, ``normal_value``;
    * ``status``: per STATUS message ``time``, ``step``, ``dt``,
      ``step_rate``, ``real_time_factor``, ``num_bodies``, ``num_sleeping``
      (docs/physics.md, "Sleeping"), ``num_contacts``, ``max_penetration``,
      and lists ``mode`` and ``method``;
    * ``joints``: per STATE with joints ``time``, ``step``; per joint
      seen ``joint_ids``, ``joint_index`` (id -> column), ``names``,
      ``model_ids``; ``position``, ``velocity``, ``effort`` (N, J: rad or m,
      rad/s or m/s, N m or N), NaN where a joint did not exist;
    * ``channels``: dict channel -> number of events (every channel).
    """
    path = os.fspath(path)
    if prefix is None:
        prefix = _detect_prefix(path)
    names = {protocol.channel(prefix, c): c.lower() for c in ("STATE", "CONTACTS", "STATUS", "JOINT_STATE")}
    joints = JointTrajectories()

    st = {k: [] for k in ("time", "step", "log_time", "state_hash", "input_digest", "kinetic_energy",
                          "potential_energy")}
    ids_per_state, rows_per_state = [], []
    ct = {k: [] for k in ("time", "step", "count", "max_depth", "normal_sum", "value_kind", "dt")}
    points = {k: [] for k in ("frame", "body_a", "body_b", "point", "normal", "depth", "normal_value")}
    ss = {k: [] for k in ("time", "step", "dt", "step_rate", "real_time_factor", "num_bodies",
                          "num_sleeping", "num_contacts", "max_penetration", "mode", "method")}
    channels = {}
    dt = None       # the latest dt known (STATUS), for impulse -> force
    t0 = None
    log = lcm.EventLog(path, "r")
    bar = _progress(log.size(), progress)
    last_pos = 0
    try:
        for event in log:
            pos = log.tell()
            bar.update(pos - last_pos)
            last_pos = pos
            channels[event.channel] = channels.get(event.channel, 0) + 1
            if t0 is None:
                t0 = event.timestamp
            kind = names.get(event.channel)
            if kind == "state":
                m = _decode_state(event)
                joints.add_state(m)
                st["time"].append(m.time)
                st["step"].append(m.step)
                st["log_time"].append((event.timestamp - t0) * 1e-6)
                st["state_hash"].append(m.state_hash & 0xFFFFFFFFFFFFFFFF)
                st["input_digest"].append(m.input_digest & 0xFFFFFFFFFFFFFFFF)
                st["kinetic_energy"].append(m.kinetic_energy)
                st["potential_energy"].append(m.potential_energy)
                ids_per_state.append(np.array([b.id for b in m.bodies], dtype=np.int64))
                rows_per_state.append(np.array(
                    [tuple(b.position) + tuple(b.orientation) + tuple(b.linear_velocity) + tuple(b.angular_velocity)
                     for b in m.bodies], dtype=np.float64).reshape(-1, 13))
                if dt is None and m.step > 0:
                    dt = m.time / m.step
            elif kind == "contacts":
                m = contacts_t.decode(event.data)
                frame = len(ct["time"])
                ct["time"].append(m.time)
                ct["step"].append(m.step)
                ct["count"].append(m.num_contacts)
                ct["max_depth"].append(max([c.depth for c in m.contacts], default=0.0))
                ct["normal_sum"].append(sum(c.normal_value for c in m.contacts))
                ct["value_kind"].append("impulse" if m.value_kind == contacts_t.IMPULSE else "force")
                ct["dt"].append(dt if dt is not None else (m.time / m.step if m.step > 0 else np.nan))
                for c in m.contacts:
                    points["frame"].append(frame)
                    points["body_a"].append(c.body_a)
                    points["body_b"].append(c.body_b)
                    points["point"].append(tuple(c.point))
                    points["normal"].append(tuple(c.normal))
                    points["depth"].append(c.depth)
                    points["normal_value"].append(c.normal_value)
            elif kind == "joint_state":
                joints.add(event.data)
            elif kind == "status":
                m = status_t.decode(event.data)
                dt = m.dt
                for k in ("time", "step", "dt", "step_rate", "real_time_factor", "num_bodies", "num_sleeping",
                          "num_contacts", "max_penetration", "method"):
                    ss[k].append(getattr(m, k))
                ss["mode"].append(MODE_NAMES.get(m.mode, str(m.mode)))
    finally:
        bar.close()
        log.close()

    body_ids, body_index, bodies = _stack_bodies(ids_per_state, rows_per_state)
    f64 = lambda v: np.asarray(v, dtype=np.float64)  # noqa: E731
    i64 = lambda v: np.asarray(v, dtype=np.int64)  # noqa: E731
    normal_sum, contact_dt = f64(ct["normal_sum"]), f64(ct["dt"])
    is_impulse = np.array([k == "impulse" for k in ct["value_kind"]], dtype=bool)
    contacts = SimpleNamespace(
        time=f64(ct["time"]), step=i64(ct["step"]), count=i64(ct["count"]), max_depth=f64(ct["max_depth"]),
        # an impulse over one step is the mean force times dt
        total_normal_force=np.where(is_impulse, normal_sum / np.where(is_impulse, contact_dt, 1.0), normal_sum),
        value_kind=list(ct["value_kind"]),
        frame=i64(points["frame"]), body_a=i64(points["body_a"]), body_b=i64(points["body_b"]),
        point=f64(points["point"]).reshape(-1, 3), normal=f64(points["normal"]).reshape(-1, 3),
        depth=f64(points["depth"]), normal_value=f64(points["normal_value"]))
    status = SimpleNamespace(**{k: f64(ss[k]) for k in ("time", "dt", "step_rate", "real_time_factor",
                                                         "max_penetration")},
                             step=i64(ss["step"]), num_bodies=i64(ss["num_bodies"]),
                             num_sleeping=i64(ss["num_sleeping"]),
                             num_contacts=i64(ss["num_contacts"]), mode=ss["mode"], method=ss["method"])
    return SimpleNamespace(
        path=path, prefix=prefix, channels=channels,
        time=f64(st["time"]), step=i64(st["step"]), log_time=f64(st["log_time"]),
        state_hash=np.asarray(st["state_hash"], dtype=np.uint64),
        input_digest=np.asarray(st["input_digest"], dtype=np.uint64),
        kinetic_energy=f64(st["kinetic_energy"]), potential_energy=f64(st["potential_energy"]),
        body_ids=body_ids, body_index=body_index,
        position=bodies[:, :, 0:3], orientation=bodies[:, :, 3:7],
        linear_velocity=bodies[:, :, 7:10], angular_velocity=bodies[:, :, 10:13],
        contacts=contacts, status=status, joints=joints.result())
