"""`make docker-check`: drives the server of the built image from this
machine with the Python client (docs/packaging.md, "Docker").

Starts the image (host network, so that LCM multicast with ttl=0 reaches
it and stays on this machine) on its packaged config and default scene,
paused in free_run mode, on a channel prefix of its own; then reads the
status, adds a sphere, steps, reads the state, and checks the free fall
against the analytic velocity. When the repository's own server is built,
the same commands go to it too and the two state hashes must be equal: the
image computes the physics of every other build (docs/snapshots.md,
"Determinism across builds"). SIGINT (the image's STOPSIGNAL) must stop
the container with exit status 0.

    .venv/bin/python scripts/docker_check.py [--image contactsim:0.1.0] [--build-dir build]
"""
import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "clients" / "python"))
sys.path.insert(0, str(REPO / "scripts"))

import contactsim  # noqa: E402
from server_process import ServerProcess, server_binary  # noqa: E402

G, DT, STEPS = 9.81, 1 / 240, 48
START_TIMEOUT = 30.0


def drive(sim):
    """The commands of the check; returns (status, state, ball id)."""
    status = sim.wait_for_server(timeout=START_TIMEOUT)
    ball = sim.add_sphere(0.1, position=(5, 5, 10), density=1000)
    sim.step(STEPS)
    return status, sim.state(), ball


def run_container(image, url, prefix):
    name = "contactsim-check-%d" % os.getpid()
    subprocess.run(["docker", "run", "-d", "--name", name, "--network", "host", image,
                    "--config", "/etc/contactsim/server.pbtxt", "--journal", "/var/lib/contactsim/journal",
                    "--no-live-line", "--lcm-url", url, "--prefix", prefix, "--mode", "free_run", "--paused"],
                   check=True, capture_output=True)
    return name


def stop_container(name):
    """docker stop (SIGINT), then the exit status and the log; removes the container."""
    subprocess.run(["docker", "stop", "-t", "15", name], check=True, capture_output=True)
    rc = int(subprocess.run(["docker", "wait", name], check=True, capture_output=True, text=True).stdout)
    log = subprocess.run(["docker", "logs", name], capture_output=True, text=True)
    subprocess.run(["docker", "rm", name], check=True, capture_output=True)
    return rc, log.stdout + log.stderr


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--image", default="contactsim:0.1.0")
    ap.add_argument("--build-dir", default=os.environ.get("CONTACTSIM_BUILD_DIR") or str(REPO / "build"))
    args = ap.parse_args()

    url = "udpm://239.255.76.67:%d?ttl=0&recv_buf_size=8388608" % (7900 + os.getpid() % 100)
    prefix = "DOCKER%d" % os.getpid()
    failures = []
    with contactsim.Client(url=url, prefix=prefix, timeout=10.0) as sim:
        t0 = time.monotonic()
        name = run_container(args.image, url, prefix)
        try:
            status, state, ball = drive(sim)
            print("image %s: server %s ready in %.1f s, %d bodies, method %s" % (
                args.image, status.version, time.monotonic() - t0, status.num_bodies, status.method))
        finally:
            rc, log = stop_container(name)
    vz = state.bodies[ball].linear_velocity[2]
    print("after add sphere and step %d: step %d, %d bodies, ball v_z %.6f m/s, state_hash %016x" % (
        STEPS, state.step, len(state.bodies), vz, state.state_hash & (2**64 - 1)))
    if status.num_bodies != 7:
        failures.append("the packaged default scene has 7 bodies, the image's server %d" % status.num_bodies)
    if state.step != STEPS or len(state.bodies) != 8:
        failures.append("expected step %d and 8 bodies" % STEPS)
    if abs(vz - (-G * STEPS * DT)) > 1e-9:
        failures.append("free fall: v_z %.12f, expected %.12f" % (vz, -G * STEPS * DT))
    if rc != 0:
        failures.append("the container exited with %d on SIGINT:\n%s" % (rc, log[-2000:]))

    if server_binary(args.build_dir).exists():
        scene = (REPO / "config" / "scenes" / "default.pbtxt").read_text()
        with ServerProcess(args.build_dir, scene_text=scene, tag="DOCKERREF") as ref:
            _, ref_state, _ = drive(ref.client)
        same = ref_state.state_hash == state.state_hash
        print("this machine's build: state_hash %016x (%s)" % (
            ref_state.state_hash & (2**64 - 1), "the same" if same else "DIFFERENT"))
        if not same:
            failures.append("the image and %s compute different worlds" % server_binary(args.build_dir))
    else:
        print("no server built in %s: the hash comparison is skipped" % args.build_dir)

    for f in failures:
        print("docker-check: FAIL: " + f, file=sys.stderr)
    print("docker-check: %s" % ("ok" if not failures else "%d failures" % len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
