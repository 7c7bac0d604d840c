"""Lockstep co-simulation against the real server: the PD example as its own
process, and the Controller helper in this one."""
import subprocess
import sys

import pytest

import contactsim

from conftest import REPO


def test_pd_example_settles_within_a_centimetre(server):
    out = subprocess.run([sys.executable, str(REPO / "clients" / "python" / "examples" / "pd_hover.py"),
                          "--lcm-url", server.url, "--prefix", server.prefix, "--seconds", "2",
                          "--target", "0.45"], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stdout + out.stderr
    assert int(out.stdout.split("final: step ")[1].split()[0]) == 480


def test_controller_inputs_act_for_one_step_and_are_digested(client):
    client.set_gravity((0, 0, 0))
    box = client.add_box((0.1, 0.1, 0.1), position=(0, 0, 1), mass=2.0)
    digests = []

    def push(state):
        digests.append(state.input_digest)
        return {box: (4.0, 0.0, 0.0)}

    with contactsim.Controller(client, push) as ctl:
        client.set_mode("lockstep")
        client.resume()
        ctl.wait_for_step(24)
        client.pause()
    st = client.state()
    # every step had 4 N on 2 kg for 1/240 s: v = 2 m/s^2 * step dt
    assert st.bodies[box].linear_velocity[0] == pytest.approx(2.0 * st.step / 240, rel=1e-9)
    assert all(d != 0 for d in digests[1:])
    # the 1 Hz heartbeat shows the mode and that the controller was released
    status = client.wait_for_status(lambda s: s.mode == "lockstep" and s.num_controllers == 0, timeout=5)
    assert status.late_events == 0


def test_input_from_an_unregistered_client_is_refused(client):
    errors = []
    client.on_reply(lambda r: errors.append(r.message) if r.code != 0 else None)
    client.send_input(1, {})
    client.step(1)  # lets the server apply the inbox
    assert any("is not a registered controller" in e for e in errors), errors


def test_a_lost_input_is_recovered_by_the_repeated_state(client):
    """The server sends STATE again while it waits and the Controller answers
    a repeated STATE by resending its input: losing an input (UDP, or one
    that raced ahead of its registration) costs a resend period, not a stall."""
    client.set_gravity((0, 0, 0))
    box = client.add_box((0.1, 0.1, 0.1), position=(0, 0, 1), mass=1.0)
    publish = client._publish_input
    sent = []

    def lossy(payload):  # drops every input of the first three steps once
        sent.append(payload)
        if len(sent) in (1, 3, 5):
            return
        publish(payload)

    client._publish_input = lossy
    errors = []
    client.on_reply(lambda r: errors.append(r.message) if r.code != 0 else None)
    with contactsim.Controller(client, lambda s: {box: (1.0, 0.0, 0.0)}, late="wait") as ctl:
        client.set_mode("lockstep")
        client.resume()
        ctl.wait_for_step(12, timeout=10)
        client.pause()
    st = client.state()
    # every step that was taken had its 1 N: none was skipped by the losses
    assert st.bodies[box].linear_velocity[0] == pytest.approx(st.step / 240, rel=1e-9)
    assert len(sent) > st.step  # the resends
    assert errors == []
