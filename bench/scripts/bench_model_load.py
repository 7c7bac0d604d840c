#!/usr/bin/env python3
"""One model of pybullet_data loaded again and again into one server (a
reset between loads), for profiling a load: the server may run under a
wrapper that runs it in the wrapper's own process (valgrind: a wrapper
that starts the server as a child, as perf stat does, is not stopped by
the interrupt at the end), so that an instruction count of the loads can
be taken. Prints each load's MODEL_CMD LOAD round trip in ms. BENCHMARKS.md,
"Robot models: load time", gives the commands.

Usage: bench/scripts/bench_model_load.py [--build-dir build] [--model iiwa|r2d2|panda] [--loads 10]
                                         [--wrap "valgrind --tool=callgrind ..."]
"""
import argparse
import os
import shlex
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MODELS = {"iiwa": "kuka_iiwa/model.urdf", "r2d2": "r2d2.urdf", "panda": "franka_panda/panda.urdf"}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"))
    ap.add_argument("--model", default="iiwa", choices=sorted(MODELS))
    ap.add_argument("--loads", type=int, default=10)
    ap.add_argument("--wrap", default="", help="a command the server runs under")
    a = ap.parse_args()
    import pybullet_data  # noqa: PLC0415
    build = os.path.abspath(a.build_dir)
    sys.path.insert(0, os.path.join(ROOT, "clients", "python"))
    os.environ["CONTACTSIM_BUILD_DIR"] = build
    import contactsim  # noqa: PLC0415
    from contactsim.process import interrupt  # noqa: PLC0415
    path = os.path.join(pybullet_data.getDataPath(), MODELS[a.model])
    prefix = "BENCHLOAD%d" % os.getpid()
    url = "udpm://239.255.76.67:%d?ttl=0&recv_buf_size=8388608" % (9800 + os.getpid() % 90)
    with tempfile.NamedTemporaryFile("w", suffix=".pbtxt", delete=False) as f:
        f.write("gravity { z: -9.81 }\n")
        scene = f.name
    server = subprocess.Popen(shlex.split(a.wrap) + [
        os.path.join(build, "bin", "contactsim-server"), "--config", os.path.join(ROOT, "config", "server.pbtxt"),
        "--scene", scene, "--lcm-url", url, "--prefix", prefix, "--mode", "free_run", "--paused", "--no-live-line",
        "--log-level", "warn"])
    try:
        # a wrapped server starts slowly and loads slowly
        with contactsim.Client(url=url, prefix=prefix, timeout=300) as c:
            c.wait_for_server(timeout=300)
            times = []
            for _ in range(a.loads):
                c.reset()
                t = time.perf_counter()
                c.load_model(path, name=a.model, fixed_base=a.model != "r2d2")
                times.append(1e3 * (time.perf_counter() - t))
            print("load %s, ms: %s" % (a.model, " ".join("%.1f" % t for t in times)))
    finally:
        interrupt(server, 60)
        os.unlink(scene)


if __name__ == "__main__":
    main()
