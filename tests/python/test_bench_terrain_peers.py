"""The peer runners on the terrain scenes (config/scenes/terrain_rain.pbtxt,
heightfield_rain.pbtxt): Bullet steps the mesh and the heightfield as its
own shapes (bench/peers/bullet_surfaces.h) and reports no body through
them; ODE and MuJoCo refuse both before stepping, naming the body and its shape."""
import json
import subprocess

import pytest

from conftest import BUILD, REPO

SCENES = {"terrain_rain": "mesh", "heightfield_rain": "heightfield"}


def run(binary, scene, *extra):
    path = BUILD / "bin" / binary
    if not path.exists():
        pytest.skip("%s is not built (its library was not found)" % binary)
    cmd = [str(path), "--scene", str(REPO / "config" / "scenes" / (scene + ".pbtxt")), "--steps", "3",
           "--repeat", "1", "--json", *extra]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    lines = [l for l in proc.stdout.splitlines() if l.startswith("{")]
    assert lines, proc.stderr
    return json.loads(lines[-1])


@pytest.mark.parametrize("scene", sorted(SCENES))
def test_bullet_steps_the_surface(scene):
    r = run("contactsim-bench-bullet", scene)
    assert r["status"] == "ok", r["status"]
    assert r["steps_done"] == 3
    assert r["bodies"] == 1001
    assert r["fell_through"] == 0


@pytest.mark.parametrize("scene", sorted(SCENES))
@pytest.mark.parametrize("binary,engine,method", [("contactsim-bench-ode", "ODE", "quickstep"),
                                                  ("contactsim-bench-mujoco", "MuJoCo", "newton")])
def test_ode_and_mujoco_refuse_the_surface(scene, binary, engine, method):
    r = run(binary, scene, "--method", method)
    assert r["status"] == ('error: %s runner: body "terrain" has shape %s; only sphere, box and plane are translated'
                           % (engine, SCENES[scene])), r["status"]
