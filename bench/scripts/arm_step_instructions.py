#!/usr/bin/env python3
"""Instructions per step of bench_models.py's held iiwa (seven position
actuators, dt 1/240 s, impulse), counted by valgrind's cachegrind on the
server: a run of 1 step and a run of 1 + STEPS steps, the difference divided
by STEPS, so that the load, the setup and the model's loading drop out. The
machine's load does not move the count, where it moves a time by a factor of
two or three. `--sleep` keeps the server's sleeping on (the held arm falls
asleep after about 150 steps); by default every step is an awake one.
`--free` counts bench_models.py's free-swinging iiwa instead (no
actuators: the arm swings from its bent pose under gravity). `--ten`
counts bench_models.py's ten bent iiwas over the ground instead (no
actuators: they swing down onto the ground and onto one another).

Usage: CONTACTSIM_BUILD_DIR=build bench/scripts/arm_step_instructions.py [--steps 200] [--sleep] [--free | --ten]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench", "scripts"))
sys.path.insert(0, os.path.join(ROOT, "clients", "python"))
import bench_models  # noqa: E402


def run(build, steps, config, models, free, ten=False):
    """Cachegrind's instruction count of a server that steps the held iiwa `steps` times."""
    import contactsim  # noqa: PLC0415
    from contactsim.process import interrupt  # noqa: PLC0415
    prefix = "ARMINSN%d" % os.getpid()
    url = "udpm://239.255.76.67:%d?ttl=0&recv_buf_size=8388608" % (9800 + os.getpid() % 90)
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "scene.pbtxt")
        with open(scene, "w") as f:
            f.write("gravity { z: -9.81 }\n")
        log = os.path.join(tmp, "cachegrind.log")
        server = subprocess.Popen(
            ["valgrind", "--tool=cachegrind", "--cache-sim=no", "--cachegrind-out-file=/dev/null",
             "--log-file=" + log, os.path.join(build, "bin", "contactsim-server"), "--config", config,
             "--scene", scene, "--lcm-url", url, "--prefix", prefix, "--mode", "free_run", "--paused",
             "--no-live-line", "--log-level", "error"])
        try:
            with contactsim.Client(url=url, prefix=prefix, timeout=600) as c:
                c.wait_for_server(timeout=300)
                c.set_timestep(bench_models.DT)
                placed = [(0, 0, 0)]
                if ten:  # bench_models.py's "ten bent iiwas", bases 0.6 m above the ground
                    c.add_plane((0, 0, 1), 0.0)
                    placed = [(0.8 * (k % 5), 0.8 * (k // 5), 0.6) for k in range(10)]
                for k, base in enumerate(placed):
                    m = c.load_model(models["iiwa"], name="iiwa%d" % k, position=base, fixed_base=True)
                    m.set_link_poses(bench_models._bent_iiwa_poses(models["iiwa"], base))
                if not free and not ten:
                    m.set_joint_targets(bench_models.IIWA_BENT, kp=bench_models.HOLD_KP, kd=bench_models.HOLD_KD)
                    m.set_effort_limits([bench_models.HOLD_EFFORT] * 7)
                c.step(10, timeout=600)
                c.step(steps, timeout=6000)
        finally:
            interrupt(server, 120)
        with open(log) as f:
            return int(re.search(r"I\s+refs:\s+([\d,]+)", f.read()).group(1).replace(",", ""))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--sleep", action="store_true", help="keep the server's sleeping on")
    ap.add_argument("--free", action="store_true", help="the free-swinging iiwa (no actuators)")
    ap.add_argument("--ten", action="store_true", help="the ten bent iiwas over the ground (no actuators)")
    a = ap.parse_args()
    build = os.environ.get("CONTACTSIM_BUILD_DIR", os.path.join(ROOT, "build"))
    import pybullet_data  # noqa: PLC0415
    models = bench_models._models(pybullet_data.getDataPath())
    # config/server.pbtxt (as bench_models.py) with sleeping as asked; its
    # scene is replaced by the empty one above
    with open(os.path.join(ROOT, "config", "server.pbtxt")) as f:
        lines = [ln for ln in f if not ln.startswith("scene:")]
    with tempfile.NamedTemporaryFile("w", suffix=".pbtxt", delete=False) as f:
        f.writelines(lines)
        f.write("sleep: %s\n" % ("true" if a.sleep else "false"))
        config = f.name
    try:
        base = run(build, 1, config, models, a.free, a.ten)
        more = run(build, 1 + a.steps, config, models, a.free, a.ten)
    finally:
        os.unlink(config)
    what = "ten bent iiwas" if a.ten else ("free iiwa" if a.free else "held iiwa")
    print("%s, %d steps%s: %.0f instructions a step" % (what, a.steps,
                                                            " (sleep on)" if a.sleep else "",
                                                              (more - base) / a.steps))


if __name__ == "__main__":
    main()
