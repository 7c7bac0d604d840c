"""Long commands against the real server (docs/protocol.md, "Long
commands"): a STEP longer than the client's timeout returns because the
server reports progress; PAUSE from another client stops a running STEP and
its reply says how far it got; a server killed mid-step is reported gone
after the timeout of silence, not waited on forever."""
import threading
import time

import pytest

import contactsim
from conftest import REPO


def _slow_server(launch):
    """box_pyramid (210 boxes) under xpbd: tens of ms a step."""
    s = launch(scene=REPO / "config" / "scenes" / "box_pyramid.pbtxt")
    s.client.set_contact_method("xpbd")
    return s


def test_a_step_longer_than_the_timeout_returns_while_progress_comes(launch):
    s = _slow_server(launch)
    # A timeout a few steps long and a STEP several timeouts long, whatever
    # this build and machine make of a step. The first steps cost more than
    # later ones (contacts form), so an estimate can run long: the STEP is
    # doubled until it does outlast the timeout.
    t0 = time.monotonic()
    s.client.step(4, timeout=60.0)
    per_step = (time.monotonic() - t0) / 4
    timeout = max(0.3, 4 * per_step)
    n = int(4 * timeout / per_step) + 1
    c = contactsim.Client(url=s.url, prefix=s.prefix, timeout=timeout)
    stepped = 4
    for _ in range(6):
        reports = []
        t0 = time.monotonic()
        r = c.step(n, progress=reports.append)
        took = time.monotonic() - t0
        stepped += n
        assert r.step == stepped and c.state().step == stepped
        assert reports and all(p.total == n and p.command == "STEP" for p in reports)
        dones = [p.done for p in reports]
        assert dones == sorted(dones) and dones[0] == 0
        if took > 1.5 * timeout:
            break
        n *= 2
    assert took > 1.5 * timeout, "no STEP outlasted the timeout (%.2f s of %.2f s)" % (took, timeout)
    c.close()


def test_pause_stops_a_running_step_and_says_how_far_it_got(launch):
    s = launch()
    s.client.add_plane((0, 0, 1), 0.0)
    for i in range(20):
        s.client.add_sphere(0.05, position=(0.2 * i, 0, 0.5), density=1000)
    stepper = contactsim.Client(url=s.url, prefix=s.prefix, timeout=5.0)
    started = threading.Event()
    outcome = {}

    def run():
        try:
            stepper.step(10_000_000, progress=lambda p: started.set())
        except contactsim.CommandError as e:
            outcome["error"] = e

    t = threading.Thread(target=run)
    t.start()
    assert started.wait(10.0), "no progress report for the running STEP"
    s.client.pause()
    t.join(20.0)
    assert not t.is_alive(), "the STEP did not end after PAUSE"
    e = outcome["error"]
    assert e.code_name == "FAILED_PRECONDITION"
    assert "cancelled by PAUSE" in e.message and "of 10000000 steps" in e.message
    taken = int(e.message.split(" after ")[1].split(" of ")[0])
    assert 0 < taken < 10_000_000
    st = s.client.wait_for_status(lambda x: x.paused and x.step > 0, timeout=5.0)
    assert st.step == e.reply.step == taken
    stepper.close()


def test_a_server_killed_mid_step_is_reported_gone(launch):
    s = launch()
    s.client.add_sphere(0.05, position=(0, 0, 0.5), density=1000)
    stepper = contactsim.Client(url=s.url, prefix=s.prefix, timeout=0.5)
    started = threading.Event()
    outcome = {}

    def run():
        t0 = time.monotonic()
        try:
            stepper.step(100_000_000, progress=lambda p: started.set())
        except contactsim.TimeoutError as e:
            outcome["error"], outcome["after"] = e, time.monotonic() - t0

    t = threading.Thread(target=run)
    t.start()
    assert started.wait(10.0)
    s.kill()
    t.join(30.0)
    assert not t.is_alive(), "the client kept waiting for a dead server"
    assert "no progress for 0.5s" in str(outcome["error"])
    stepper.close()


def test_a_deadline_ends_the_wait_even_while_progress_comes(launch):
    s = launch()
    s.client.add_sphere(0.05, position=(0, 0, 0.5), density=1000)
    c = contactsim.Client(url=s.url, prefix=s.prefix, timeout=5.0)
    with pytest.raises(contactsim.TimeoutError, match="by the deadline"):
        c.step(100_000_000, deadline=0.5)
    s.client.pause()  # stops the steps the server is still taking
    c.close()
