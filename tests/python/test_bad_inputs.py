"""The bad-input catalogue (bad_input_cases.py) against one real server:
each case gets its reply code, a message naming the field and the value,
and leaves the world as it was: the STATE after it (hash, clock and every
body, bit for bit) is the STATE before it, and at the end no body or joint
id has been used up. scripts/bad_input_table.py renders the same cases
with their replies for docs/reliability.md."""

import pytest

import contactsim
from contactsim import reply_t

import bad_input_cases as bad
from conftest import Server, current_state

GRAVITY = (0.0, 0.0, -9.81)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    return tmp_path_factory.mktemp("bad-inputs")


@pytest.fixture(scope="module")
def catalogue(files):
    bad.write_files(files)
    return bad.cases(files)


CASES = bad.cases("/unused")
CASE_IDS = [c.id for c in CASES]


@pytest.fixture(scope="module")
def world(files):
    scene = files / "scene.pbtxt"
    scene.write_text(bad.SCENE)
    server = Server(files, scene)
    client = server.client
    client.step(2)
    yield server
    assert server.proc.poll() is None, "server died:\n" + server.log()
    server.stop()


def test_the_catalogue_covers_every_channel_and_op(catalogue):
    assert len(catalogue) >= 60
    ops = {(c.channel, c.op) for c in catalogue}
    body_ops = {"ADD", "REMOVE", "SET_POSE", "SET_VELOCITY", "APPLY_FORCE", "APPLY_IMPULSE", "SET_MASS", "SET_MATERIAL",
                "SET_FILTER"}
    scene_ops = {"LOAD_SCENE", "SET_GRAVITY", "SET_TIMESTEP", "SET_METHOD", "STEP", "SET_MODE", "SNAPSHOT", "RESTORE",
                 "REWIND", "REGISTER_CONTROLLER", "RELEASE_CONTROLLER"}
    assert {("BODY_CMD", o) for o in body_ops} <= ops
    assert {("SCENE_CMD", o) for o in scene_ops} <= ops
    assert {("JOINT_CMD", "ADD"), ("JOINT_CMD", "REMOVE"), ("INPUT", "input")} <= ops
    assert {c.code for c in catalogue} >= {reply_t.INVALID_ARGUMENT, reply_t.NOT_FOUND, reply_t.FAILED_PRECONDITION,
                                           reply_t.DECODE_ERROR, reply_t.RESOURCE_EXHAUSTED}


@pytest.mark.parametrize("index", [
    pytest.param(i, marks=pytest.mark.xfail(strict=True, reason=c.gap)) if c.gap else i for i, c in enumerate(CASES)],
    ids=CASE_IDS)
def test_bad_input_is_refused_with_a_message_naming_it_and_changes_nothing(world, catalogue, index):
    case = catalogue[index]
    client = world.client
    before = current_state(client, GRAVITY)
    r = case.send(client)
    assert r is not None
    name = contactsim.errors.CODE_NAMES.get(r.code, r.code)
    if case.code is None:
        assert r.code != reply_t.OK, "accepted: %s" % r.message
    else:
        assert r.code == case.code, "%s (%s), want %s" % (name, r.message, contactsim.errors.CODE_NAMES[case.code])
    for w in case.words:
        assert w in r.message, "message %r does not name %r" % (r.message, w)
    assert world.proc.poll() is None, "server died:\n" + world.log()
    after = current_state(client, GRAVITY)
    assert after == before, "the world changed"


def test_no_body_or_joint_id_was_used_up(world):
    client = world.client
    state = current_state(client, GRAVITY)
    assert sorted(state.bodies) == sorted(bad.IDS.values())
    assert client.add_sphere(0.05, position=(8, 8, 1)) == max(bad.IDS.values()) + 1
    assert client.add_joint("ball", bad.IDS["ball"], None, anchor=(0, 0, 1)) == max(bad.JOINTS) + 1
