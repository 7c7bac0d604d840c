"""The MuJoCo peer of the scene benchmark (bench/peers/mujoco_runner.cpp),
built against the mujoco-core wheel in .venv: it is built whenever the venv
holds the wheel, it keeps an aligned stack at rest, its thread pool changes
no result, and bench/scripts/bench_scenes.py gives it the same --threads as contactsim."""
import importlib.util
import json
import subprocess
from pathlib import Path

import pytest

from conftest import BUILD, REPO, load_script

RUNNER = BUILD / "bin" / "contactsim-bench-mujoco"


def wheel_version():
    """MuJoCo's header version in this venv's wheel (0 when there is none)."""
    spec = importlib.util.find_spec("mujoco")
    if not spec or not spec.submodule_search_locations:
        return 0
    header = Path(spec.submodule_search_locations[0]) / "include" / "mujoco" / "mujoco.h"
    if not header.exists():
        return 0
    for line in header.read_text().splitlines():
        if line.startswith("#define mjVERSION_HEADER"):
            return int(line.split()[-1])
    return 0


def run(scene, *args):
    proc = subprocess.run([str(RUNNER), "--scene", str(scene), "--repeat", "1", "--json", *args],
                          capture_output=True, text=True, timeout=300)
    return json.loads(proc.stdout.splitlines()[-1])


@pytest.fixture(scope="module")
def runner():
    if wheel_version() < 3010000:
        pytest.skip("no mujoco-core wheel of 3.10 or later in this venv (make deps)")
    if not (BUILD / "CMakeCache.txt").exists():
        pytest.skip("%s is not configured (run `make`)" % BUILD)
    # the wheel is there, so CMake must have found it (bench/peers/CMakeLists.txt)
    assert RUNNER.exists(), "the venv has the mujoco-core wheel but %s was not built" % RUNNER
    return RUNNER


def test_aligned_stack_stays_at_rest(runner):
    # 8 aligned cubes have no reason to move; MuJoCo's soft contacts let them
    # sink a little (a fraction of a mm per contact at the default solref)
    r = run(REPO / "bench" / "scenes" / "stack8.pbtxt", "--steps", "240", "--threads", "1")
    assert r["status"] == "ok", r["status"]
    assert r["params"]["solver"] == "newton"
    assert r["max_penetration"] < 1e-3
    assert r["top_displacement"] < 5e-3


def test_thread_pool_changes_no_result(runner):
    # 1,000 spheres landing: the pool spreads collision detection and the
    # islands over the threads, each writing its own slots
    scene = REPO / "config" / "scenes" / "sphere_pile.pbtxt"
    one = run(scene, "--method", "cg", "--steps", "120", "--threads", "1")
    two = run(scene, "--method", "cg", "--steps", "120", "--threads", "2")
    assert (one["threads"], two["threads"]) == (1, 2)
    assert one["status"] == two["status"] == "ok"
    assert one["max_penetration"] > 0  # the spheres have landed
    for key in ("max_penetration", "final_kinetic_energy"):
        assert one[key] == two[key]


def test_bench_scenes_gives_mujoco_the_threads(monkeypatch):
    bench_scenes = load_script("bench/scripts/bench_scenes.py")

    seen = []

    class Done:
        returncode, stdout, stderr = 0, '{"status": "ok"}\n', ""

    monkeypatch.setattr(bench_scenes.subprocess, "run", lambda cmd, **kw: seen.append(cmd) or Done())
    args = type("Args", (), {"repeat": 1, "max_seconds": 1.0, "threads": 2, "steps": 0})()
    for binary in ("contactsim-bench", "contactsim-bench-mujoco", "contactsim-bench-bullet"):
        bench_scenes.run_one("/bin", binary, "bounce", "m", [], args)
    threads = [cmd[cmd.index("--threads") + 1] if "--threads" in cmd else None for cmd in seen]
    assert threads == ["2", "2", None]
