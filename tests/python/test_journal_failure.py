"""A journal the disk refuses, against the real server: the commands it
could not record are answered INTERNAL and not applied, and a server
restarted on the folder recovers exactly the acknowledged bodies.

The disk is made to refuse by a file size limit on the server process
(prlimit --fsize: writes past it fail with EFBIG, and the server ignores
SIGXFSZ so that it gets the error instead of dying)."""
import shutil

import pytest

import contactsim

pytestmark = pytest.mark.skipif(shutil.which("prlimit") is None, reason="needs prlimit (util-linux)")


def _add_until_refused(client, limit):
    ok, refused = [], []
    for i in range(limit):
        try:
            ok.append(client.add_sphere(0.05, position=(0.2 * i, 0, 1), density=1000))
        except contactsim.CommandError as e:
            refused.append(e)
            if len(refused) >= 3:
                break
    return ok, refused


def test_a_full_journal_answers_internal_and_recovery_keeps_what_was_acknowledged(launch, tmp_path):
    journal = tmp_path / "journal"
    # room for the first snapshot and a few dozen records
    s = launch(args=("--journal", str(journal)), wrapper=("prlimit", "--fsize=12000", "--"))
    c = s.client
    ok, refused = _add_until_refused(c, 400)
    assert ok, "no ADD was acknowledged before the journal filled"
    assert refused, "the journal never refused a record"
    for e in refused:
        assert e.code_name == "INTERNAL"
        assert "not applied" in e.message and "journal" in e.message
    # a STATE follows the changes of a paused server; the last one holds the acknowledged bodies
    st = c.wait_for_state(lambda x: sorted(x.bodies) == sorted(ok), timeout=5.0)
    assert sorted(st.bodies) == sorted(ok)
    status = c.wait_for_status(lambda x: x.commands_rejected >= len(refused), timeout=5.0)
    assert "journal" in status.last_error
    s.kill()  # as a crash: only the journal carries the world over

    s2 = launch(args=("--journal", str(journal)))
    st = s2.client.wait_for_state(lambda x: True, timeout=5.0)
    assert sorted(st.bodies) == sorted(ok)
