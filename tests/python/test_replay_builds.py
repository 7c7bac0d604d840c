"""A run recorded from one build replays identically on every other build
(docs/snapshots.md, "Determinism across builds"): a server of the build
under test is recorded with lcm-logger while the determinism scene (a stack,
a slide, a bounce, a pendulum and a hinge) runs through every registered
contact method, and ``contactsim-server --replay`` of that log must agree
at every STATE on this build and on each other build of this clone that
exists: in CI the sanitizer suite (Debug -O1, ASan and UBSan) replays the
log it records on the RelWithDebInfo build as well as on its own."""
import subprocess

import pytest

import contactsim

from conftest import BUILD, CONFIG, REPO, SERVER_BIN, method_names
from lcm_recorder import LcmRecorder
from test_replay import complete

SCENE = REPO / "config" / "scenes" / "determinism.pbtxt"
STEPS_PER_METHOD = 40
RECORD_TRIES = 3  # a log that lost a message on UDP, or a run that lost a reply, is recorded again


def servers_of_every_build():
    """The server under test first, then the other builds' servers."""
    found = [SERVER_BIN]
    for folder in ("build", "build-asan"):
        other = (REPO / folder).resolve()
        binary = other / "bin" / "contactsim-server"
        if other != BUILD and binary.exists():
            found.append(binary)
    return found


SCENE_JOINTS = (1, 2)  # the scene's pendulum and hinge, numbered in file order


def run_through_every_method(client):
    """Every method in turn, lcp with both solvers; a method that refuses
    joints or restitution (barrier; docs/physics.md, "Method contract")
    comes last, after the scene's joints are removed and every body's
    restitution is set to 0."""
    methods = method_names(client)
    runs = [(m, {}) for m in methods if m != "lcp"]
    if "lcp" in methods:
        runs += [("lcp", {"solver": "pgs"}), ("lcp", {"solver": "lemke"})]
    refused = []
    for name, params in runs:
        try:
            client.set_contact_method(name, **params)
        except contactsim.TimeoutError:
            raise  # a lost reply, not a refusal (it subclasses CommandError)
        except contactsim.CommandError as e:
            assert "joint" in str(e) or "restitution" in str(e), str(e)
            refused.append((name, params))
            continue
        client.step(STEPS_PER_METHOD)
    for jid in SCENE_JOINTS if refused else ():
        client.remove_joint(jid)
    for body in sorted(client.state().bodies) if refused else ():
        client.set_material(body, restitution=0.0)
    for name, params in refused:
        client.set_contact_method(name, **params)
        client.step(STEPS_PER_METHOD)
    return len(runs)


def test_a_run_through_every_method_replays_identically_on_every_build(launch, tmp_path):
    if not SERVER_BIN.exists():
        pytest.skip("%s is not built" % SERVER_BIN)
    for attempt in range(RECORD_TRIES):
        server = launch(scene=SCENE)
        log = tmp_path / ("run%d.lcmlog" % attempt)
        try:
            with LcmRecorder(server.url, server.prefix + "_.*", log):
                runs = run_through_every_method(server.client)
        except contactsim.TimeoutError:
            # a reply lost on UDP (seen once under the sanitizers, the
            # machine loaded): the run is recorded again on a new server
            continue
        if complete(log, server.prefix, server.client):
            break
    else:
        pytest.fail("every recording lost a command, a reply or an input on UDP")
    for binary in servers_of_every_build():
        out = subprocess.run([str(binary), "--config", str(CONFIG), "--scene", str(SCENE),
                              "--prefix", server.prefix, "--replay", str(log)],
                             capture_output=True, text=True, timeout=600)
        assert out.returncode == 0, "%s: %s%s" % (binary, out.stdout, out.stderr[-2000:])
        assert out.stdout.startswith("identical: "), out.stdout
        # compared up to the last method's last step, not only the first ones
        assert "to %d)" % (runs * STEPS_PER_METHOD) in out.stdout, out.stdout
