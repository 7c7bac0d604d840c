"""Snapshots, restore, rewind and crash recovery against the real server."""
import re
import threading

import pytest

import contactsim

from conftest import method_names


def build(client, elastic=True):
    """Bodies with the server's default restitution and a bouncy sphere, or
    all with restitution 0 for a method that simulates none (barrier;
    docs/physics.md, "Method contract")."""
    e = {} if elastic else {"restitution": 0.0}
    client.add_plane((0, 0, 1), 0.0, friction=0.6, **e)
    box = client.add_box((0.1, 0.1, 0.1), position=(0, 0, 0.1), velocity=(0.6, 0, 0), **e)
    client.add_box((0.1, 0.1, 0.1), position=(0.7, 0, 0.1), **e)
    client.add_sphere(0.1, position=(0.7, 0, 0.5), restitution=0.4 if elastic else 0.0)
    return box


def hashes(client, n, box):
    out = []
    for i in range(n):
        if i == 5:
            client.apply_impulse(box, (0, 0.2, 0))
        out.append(client.step(1).step and client.state().state_hash)
    return out


def test_restore_and_rewind_repeat_every_step_for_every_method(client):
    for name in method_names(client):
        client.reset()
        client.set_contact_method(name)
        contract = client.wait_for_status(lambda s: s.method == name, timeout=5.0).contract()
        box = build(client, elastic=contract["restitution"])
        client.step(20)
        client.snapshot("k")
        original = hashes(client, 30, box)
        client.restore("k")
        assert client.step(1).step == 21
        client.rewind(20)
        assert hashes(client, 30, box) == original, name
        r = client.rewind(37)
        assert r.step == 37
        assert client.step(1).step == 38 and client.state().state_hash == original[17], name


def test_file_snapshots_and_refusals(client, tmp_path):
    build(client)
    client.step(10)
    path = tmp_path / "k.pb"
    client.snapshot(path=path)
    assert path.stat().st_size > 0
    h = client.step(5).step and client.state().state_hash
    client.restore(path=path)
    assert client.step(5).step == 15 and client.state().state_hash == h
    with pytest.raises(contactsim.CommandError, match='no snapshot named "nope"'):
        client.restore("nope")
    with pytest.raises(contactsim.CommandError, match=r"step must be in \[10, 15\]"):
        client.rewind(99)
    with pytest.raises(ValueError):
        client.snapshot()


def test_killed_server_recovers_every_acknowledged_command(launch, tmp_path):
    """Commands stream in from a thread; the server is SIGKILLed in the
    middle. Restarted on the same journal folder, it must hold every body
    whose ADD was acknowledged, at its position, and the last acknowledged
    step."""
    journal = tmp_path / "journal"
    first = launch(args=("--journal", str(journal)))
    c = first.client
    c.set_gravity((0, 0, 0))
    acked = {}
    last_step = [0]
    done = threading.Event()

    def stream():
        try:
            for i in range(100000):
                p = (0.2 * i, 0.0, 1.0)  # apart: no contact moves them
                acked[c.add_sphere(0.05, position=p)] = p
                if i % 10 == 9:
                    last_step[0] = c.step(3).step
        except Exception:  # the kill cuts the stream: whatever is in flight is lost
            pass
        done.set()

    t = threading.Thread(target=stream, daemon=True)
    t.start()
    while len(acked) < 60:
        t.join(0.01)
    first.kill()
    done.wait(10)
    snapshot_of_acked = dict(acked)
    assert len(snapshot_of_acked) >= 60

    second = launch(args=("--journal", str(journal)))
    st = second.client.step(1)
    bodies = second.client.state().bodies
    assert st.step >= last_step[0] + 1
    missing = [i for i in snapshot_of_acked if i not in bodies]
    assert not missing, "acknowledged bodies lost: %s" % missing[:10]
    for i, p in snapshot_of_acked.items():
        assert tuple(bodies[i].position) == pytest.approx(p, abs=1e-12)
