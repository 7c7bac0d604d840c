#!/usr/bin/env python3
"""Robot models beside PyBullet (DIRECT mode, the same URDFs, the same dt):
load time of each model, and ms per step of one free-swinging iiwa, ten
iiwas on a table, R2D2 on the ground, and one iiwa held at a bent pose by
seven position actuators (contactsim's joint actuators; PyBullet's
POSITION_CONTROL motors at their default gains with the same effort limit). contactsim runs as a server
(free_run, paused, driven by STEP over LCM on this host), so its load time
includes reading the files, building the hulls and one command round trip,
and its step time is a STEP of many steps divided by their count. Prints a
markdown table of the medians of --repeat runs (each run a fresh PyBullet
process and a fresh server), with each process's peak resident memory
(VmHWM: the server's, and the PyBullet process's, Python included);
docs/models.md and BENCHMARKS.md, "Robot models", say how it was run.

Usage: bench/scripts/bench_models.py [--build-dir build] [--method impulse] [--steps 2000] [--scene WORD]
                                     [--repeat 3] [--max-hull-vertices N]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DT = 1.0 / 240.0


def _models(data):
    return {"iiwa": os.path.join(data, "kuka_iiwa", "model.urdf"),
            "r2d2": os.path.join(data, "r2d2.urdf"),
            "panda": os.path.join(data, "franka_panda", "panda.urdf")}


# The scenes: (name, [(model, position, fixed_base, bent)], ground, held by position actuators)
IIWA_BENT = [0.3, 0.8, -0.4, -1.2, 0.5, 0.7, -0.3]
SCENES = [
    ("one free-swinging iiwa", [("iiwa", (0, 0, 0), True, True)], False, False),
    ("ten bent iiwas, bases 0.6 m above the ground", [("iiwa", (0.8 * (i % 5), 0.8 * (i // 5), 0.6), True, True) for i in range(10)], True, False),
    ("R2D2 on the ground", [("r2d2", (0, 0, 0.5), False, False)], True, False),
    ("one iiwa held by seven position actuators", [("iiwa", (0, 0, 0), True, True)], False, True),
]
# The held iiwa's gains and effort limit: N m/rad, N m s/rad, N m. PyBullet's
# motors are velocity rows of its solver with their own gain scale, so only
# the effort limit is shared; both hold the pose, and the row is a step's cost.
HOLD_KP, HOLD_KD, HOLD_EFFORT = 2000.0, 100.0, 300.0


def _bent_iiwa_poses(path, base):
    """{link: (p, R)} of the iiwa at IIWA_BENT with its base at `base`, by pinocchio."""
    import numpy as np  # noqa: PLC0415
    import pinocchio as pin  # noqa: PLC0415
    model = pin.buildModelFromUrdf(path)
    data = model.createData()
    pin.framesForwardKinematics(model, data, np.array(IIWA_BENT))
    return {f.name: (np.asarray(base) + data.oMf[i].translation, data.oMf[i].rotation)
            for i, f in enumerate(model.frames) if f.type == pin.FrameType.BODY}


def _peak_rss_mb(pid="self"):
    """A process's peak resident set (VmHWM), MB."""
    with open("/proc/%s/status" % pid) as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def bench_pybullet_child(steps, scene):
    """bench_pybullet in a process of its own, so that its memory is its own."""
    out = subprocess.run([sys.executable, os.path.abspath(__file__), "--pybullet-child", "--steps", str(steps),
                          "--scene", scene], capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def bench_pybullet(models, steps):
    import pybullet as p  # noqa: PLC0415
    out = {"load": {}, "step": {}}
    cid = p.connect(p.DIRECT)
    for name, path in models.items():
        p.resetSimulation(physicsClientId=cid)
        t = time.perf_counter()
        p.loadURDF(path, useFixedBase=name != "r2d2", physicsClientId=cid)
        out["load"][name] = 1e3 * (time.perf_counter() - t)
    for title, placed, ground, held in SCENES:
        p.resetSimulation(physicsClientId=cid)
        p.setGravity(0, 0, -9.81, physicsClientId=cid)
        p.setTimeStep(DT, physicsClientId=cid)
        if ground:
            p.loadURDF(os.path.join(os.path.dirname(models["iiwa"]), "..", "plane.urdf"), physicsClientId=cid)
        for name, pos, fixed, bent in placed:
            uid = p.loadURDF(models[name], pos, useFixedBase=fixed, physicsClientId=cid)
            for j in range(p.getNumJoints(uid, physicsClientId=cid)):
                # passive joints: PyBullet's default velocity motors off
                p.setJointMotorControl2(uid, j, p.VELOCITY_CONTROL, force=0, physicsClientId=cid)
                if bent:
                    p.resetJointState(uid, j, IIWA_BENT[j], physicsClientId=cid)
                if held:
                    p.setJointMotorControl2(uid, j, p.POSITION_CONTROL, targetPosition=IIWA_BENT[j],
                                            force=HOLD_EFFORT, physicsClientId=cid)
        t = time.perf_counter()
        for _ in range(steps):
            p.stepSimulation(physicsClientId=cid)
        out["step"][title] = 1e3 * (time.perf_counter() - t) / steps
    p.disconnect(cid)
    out["rss_mb"] = _peak_rss_mb()
    return out


def bench_contactsim(models, steps, build, method, max_hull_vertices):
    sys.path.insert(0, os.path.join(ROOT, "clients", "python"))
    os.environ["CONTACTSIM_BUILD_DIR"] = build
    import contactsim  # noqa: PLC0415
    from contactsim.process import interrupt  # noqa: PLC0415
    out = {"load": {}, "step": {}}
    prefix = "BENCHMODELS%d" % os.getpid()
    url = "udpm://239.255.76.67:%d?ttl=0&recv_buf_size=8388608" % (9900 + os.getpid() % 90)
    with tempfile.NamedTemporaryFile("w", suffix=".pbtxt", delete=False) as f:
        f.write("gravity { z: -9.81 }\n")
        scene = f.name
    server = subprocess.Popen([os.path.join(build, "bin", "contactsim-server"), "--config",
                               os.path.join(ROOT, "config", "server.pbtxt"), "--scene", scene, "--lcm-url", url,
                               "--prefix", prefix, "--mode", "free_run", "--paused", "--no-live-line",
                               "--log-level", "warn"])
    try:
        with contactsim.Client(url=url, prefix=prefix, timeout=30) as c:
            c.wait_for_server(timeout=15)
            c.set_contact_method(method)
            for name, path in models.items():
                c.reset()
                t = time.perf_counter()
                c.load_model(path, name=name, fixed_base=name != "r2d2", max_hull_vertices=max_hull_vertices)
                out["load"][name] = 1e3 * (time.perf_counter() - t)
            for title, placed, ground, held in SCENES:
                c.reset()
                c.set_timestep(DT)
                if ground:
                    c.add_plane((0, 0, 1), 0.0)
                for k, (name, pos, fixed, bent) in enumerate(placed):
                    m = c.load_model(models[name], name="%s%d" % (name, k), position=pos, fixed_base=fixed,
                                     max_hull_vertices=max_hull_vertices)
                    if bent:
                        m.set_link_poses(_bent_iiwa_poses(models["iiwa"], pos))
                    if held:
                        m.set_joint_targets(IIWA_BENT, kp=HOLD_KP, kd=HOLD_KD)
                        m.set_effort_limits([HOLD_EFFORT] * 7)
                c.step(10, timeout=60)  # warm: caches and first contacts
                t = time.perf_counter()
                c.step(steps, timeout=600)
                out["step"][title] = 1e3 * (time.perf_counter() - t) / steps
            out["rss_mb"] = _peak_rss_mb(server.pid)
    finally:
        interrupt(server, 10)
        os.unlink(scene)
    return out


def _median(runs, *keys):
    vals = []
    for r in runs:
        for k in keys:
            r = r[k]
        vals.append(r)
    return statistics.median(vals)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"))
    ap.add_argument("--method", default="impulse")
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--scene", default="", help="only the scenes whose title contains this word")
    ap.add_argument("--repeat", type=int, default=3, help="runs of each; the table gives their medians")
    ap.add_argument("--max-hull-vertices", type=int, default=0,
                    help="contactsim's hull budget per mesh (0: the server's default, -1: full hulls)")
    ap.add_argument("--pybullet-child", action="store_true", help=argparse.SUPPRESS)
    a = ap.parse_args()
    SCENES[:] = [s for s in SCENES if a.scene in s[0]]
    import pybullet_data  # noqa: PLC0415
    models = _models(pybullet_data.getDataPath())
    if a.pybullet_child:
        print(json.dumps(bench_pybullet(models, a.steps)))
        return
    pb, cs = [], []
    for _ in range(a.repeat):
        pb.append(bench_pybullet_child(a.steps, a.scene))
        cs.append(bench_contactsim(models, a.steps, os.path.abspath(a.build_dir), a.method, a.max_hull_vertices))
    print("| what | contactsim (%s), ms | PyBullet DIRECT, ms | ratio |" % a.method)
    print("|---|---:|---:|---:|")
    for kind, rows in (("load", list(models)), ("step", [t for t, _, _, _ in SCENES])):
        for row in rows:
            c, p = _median(cs, kind, row), _median(pb, kind, row)
            label = "load %s" % row if kind == "load" else "step: %s" % row
            print("| %s | %.3f | %.3f | %.2f |" % (label, c, p, c / p))
    c, p = _median(cs, "rss_mb"), _median(pb, "rss_mb")
    print("| peak resident memory, MB (server; PyBullet's Python process) | %.1f | %.1f | %.2f |" % (c, p, c / p))


if __name__ == "__main__":
    main()
