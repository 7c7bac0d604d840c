"""The Box3D peer of the scene benchmark (bench/peers/box3d_runner.cpp),
built only when CMake was given a Box3D checkout (CONTACTSIM_BOX3D_SOURCE_DIR
or BOX3D_SOURCE_DIR): it gets the scene's bodies and masses, its task
callbacks change no result, and bench/scripts/bench_scenes.py puts its row
beside Bullet's and sets soft's speed target against its measured ratio."""
import json
import subprocess

import pytest

from conftest import BUILD, REPO, load_script

RUNNER = BUILD / "bin" / "contactsim-bench-box3d"
CONTACTSIM = BUILD / "bin" / "contactsim-bench"
# Box3D steps in single precision: a kinetic energy summed over 1,000 bodies
# in float agrees with the double one to a few float epsilons (1.2e-7) a body
FLOAT_REL = 1e-5


def run(binary, scene, *args):
    proc = subprocess.run([str(binary), "--scene", str(REPO / "config" / "scenes" / (scene + ".pbtxt")),
                           "--repeat", "1", "--json", *args], capture_output=True, text=True, timeout=120)
    return json.loads(proc.stdout.splitlines()[-1])


@pytest.fixture(scope="module")
def runner():
    if not RUNNER.exists():
        pytest.skip("no Box3D runner in %s (configure with -DCONTACTSIM_BOX3D_SOURCE_DIR=PATH)" % BUILD)
    return RUNNER


@pytest.mark.parametrize("scene", ["sphere_pile", "box_rain"])
def test_bodies_and_masses_match_contactsim(runner, scene):
    # every body starts in the air: after one step each falls at g dt, so the
    # kinetic energy, 1/2 (g dt)^2 times the total mass, weighs the bodies
    box3d = run(runner, scene, "--steps", "1", "--threads", "1")
    ours = run(CONTACTSIM, scene, "--method", "soft", "--steps", "1", "--threads", "1")
    assert box3d["status"] == ours["status"] == "ok"
    assert box3d["bodies"] == ours["bodies"]
    assert box3d["max_penetration"] == 0
    assert box3d["final_kinetic_energy"] == pytest.approx(ours["final_kinetic_energy"], rel=FLOAT_REL)


def test_task_callbacks_change_no_result(runner):
    # Box3D's solver is deterministic across worker counts; two workers run
    # its loops through the runner's enqueue/finish pool
    one = run(runner, "box_rain", "--steps", "40", "--threads", "1")
    two = run(runner, "box_rain", "--steps", "40", "--threads", "2")
    assert (one["threads"], two["threads"]) == (1, 2)
    assert one["status"] == two["status"] == "ok"
    for key in ("max_penetration", "min_distance", "final_kinetic_energy"):
        assert one[key] == two[key]


def test_bench_scenes_runs_box3d_beside_bullet(monkeypatch):
    bench_scenes = load_script("bench/scripts/bench_scenes.py")

    class Listed:
        returncode, stdout, stderr = 0, "impulse soft\n", ""

    monkeypatch.setattr(bench_scenes.os.path, "exists", lambda path: True)
    monkeypatch.setattr(bench_scenes.subprocess, "run", lambda cmd, **kw: Listed())
    rows = [(engine, method) + tuple(params) for engine, _, method, params in bench_scenes.runs("/bin")]
    assert rows[:3] == [("bullet", "sequential_impulse"), ("box3d", "soft_step"), ("contactsim", "impulse")]
    assert ("contactsim", "soft", "precision=float") in rows
    cmd = bench_scenes.runner_command("/bin", "contactsim-bench-box3d", "box_rain", "soft_step", [], 2)
    assert cmd[cmd.index("--threads") + 1] == "2"


def soft_lines(box3d_ms):
    bench_scenes = load_script("bench/scripts/bench_scenes.py")
    rows = [("bullet", "sequential_impulse", 10.0, 100), ("contactsim", "soft", 5.0, 60)]
    if box3d_ms:
        rows.append(("box3d", "soft_step", box3d_ms, 30))
    results = [{"scene_name": "box_rain", "engine": e, "label": l, "ms_per_step": ms, "status": "ok",
                "instructions_per_step": n} for e, l, ms, n in rows]
    return bench_scenes.soft_targets(results, lambda s, e, l: next(
        (r for r in results if (r["scene_name"], r["engine"], r["label"]) == (s, e, l)), None))


def test_soft_target_is_box3d_ratio_of_the_same_run():
    assert soft_lines(4.0) == ["* box_rain, soft: 0.50x Bullet's ms/step against Box3D's 0.40x "
                               "(**missed by 25%**); in instructions 0.60x against 0.30x."]
    assert soft_lines(6.0)[0].startswith("* box_rain, soft: 0.50x Bullet's ms/step against Box3D's 0.60x (met)")
    # without a Box3D row nothing is compared
    assert "**not checked**, no completed Box3D row (no runner;" in soft_lines(None)[0]
