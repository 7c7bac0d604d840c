"""The joint channels against a real server (docs/actuators.md, "Joint
channels"): JOINT_STATE's joints, names and order; ACTUATOR_CMD round trips
and refusals; lockstep joint commands; JOINT_STATE read back from an
lcm-logger log; both command lines. The tests that need the actuators to
move the bodies (the engine's actuator rows) probe for them first and skip
with the reason while an actuator applies nothing.
"""
import math
import os
import subprocess
import time

import numpy as np
import pytest

import contactsim
from contactsim.logread import read_log

from conftest import BUILD
from lcm_recorder import LcmRecorder
from test_cli import cli

pybullet_data = pytest.importorskip("pybullet_data")
IIWA = os.path.join(pybullet_data.getDataPath(), "kuka_iiwa", "model.urdf")
IIWA_JOINTS = ["lbr_iiwa_joint_%d" % i for i in range(1, 8)]
CTL = BUILD / "bin" / "contactsim-ctl"


@pytest.fixture
def arm_server(launch):
    return launch(args=("--model-path", pybullet_data.getDataPath()))


def _pendulum(c, *, x=0.0, length=0.5, mass=1.0):
    """A sphere of radius 0.05 m on a massless rod: a box hinged about y at
    (x, 0, 2), its centre `length` below. Returns (body, joint)."""
    bob = c.add_sphere(0.05, position=(x, 0, 2 - length), mass=mass)
    return bob, c.add_joint("hinge", bob, None, anchor=(x, 0, 2), axis=(0, 1, 0))


def actuators_apply(c):
    """True when a joint's actuator moves its bodies: a 1 N m torque on a
    free hinge in zero gravity turns it within ten steps."""
    c.set_gravity((0, 0, 0))
    bob, hinge = _pendulum(c, x=50.0)
    c.set_joint_actuator(hinge, torque=1.0)
    c.step(10)
    moved = abs(c.request_joint_state().of_joints([hinge])[1][0]) > 1e-9
    c.remove_body(bob)
    c.set_gravity((0, 0, -9.81))
    return moved


def need_actuators(c):
    if not actuators_apply(c):
        pytest.skip("the engine's actuators apply nothing yet: a 1 N m torque leaves a free hinge at rest")


# ---------------------------------------------------------------- channels
def test_joint_state_names_the_models_joints_in_order_then_loose_ones(arm_server):
    c = arm_server.client
    arm = c.load_model(IIWA, name="arm", fixed_base=True)
    assert arm.actuated_joints == IIWA_JOINTS
    _, hinge = _pendulum(c, x=2.0)
    bob = c.add_sphere(0.05, position=(3, 0, 1))
    c.add_joint("distance", bob, None, anchor=(3, 0, 2))   # no coordinate: not listed
    c.step(4)
    st = c.state()
    js = c.request_joint_state()
    assert js.step == st.step == 4
    assert list(js.joint_ids) == [arm.joint_id(n) for n in IIWA_JOINTS] + [hinge]
    assert list(js.model_ids) == [arm.id] * 7 + [0]
    assert js.names == IIWA_JOINTS + [str(hinge)]
    q, v, u = arm.joint_state()
    assert q.shape == v.shape == u.shape == (7,)
    assert np.all(np.isfinite(q)) and np.all(u == 0.0)
    # published with every STATE, just before it: the STEP's reply waits for its STATE
    c.step(1)
    assert c.joint_state().step == c.state().step == 5
    # STATE carries the same joints: named from MODEL_INFO, equal bit for bit
    st = c.state()
    from_state = c.joints_of(st)
    published = c.request_joint_state()
    assert published.step == from_state.step == 5
    assert list(from_state.joint_ids) == list(published.joint_ids)
    assert list(from_state.model_ids) == list(published.model_ids)
    assert from_state.names == published.names
    for a, b in ((from_state.positions, published.positions), (from_state.velocities, published.velocities),
                 (from_state.efforts, published.efforts)):
        np.testing.assert_array_equal(a, b)


def test_a_lockstep_controller_reads_its_joints_from_state_alone(arm_server):
    """While a controller is registered in lockstep the server sends no
    JOINT_STATE (joint_state "outside_lockstep", the default): the
    controller's joints, Model.joint_state() and Client.joint_state() come
    from STATE, of the step just taken."""
    c = arm_server.client
    arm = c.load_model(IIWA, name="arm", fixed_base=True)
    arm.set_joint_targets(np.full(7, 0.1), kp=400.0, kd=40.0)
    heard, seen = [], {}
    remove = c.on_joint_state(heard.append)

    def policy(state, joints):
        seen[state.step] = joints
        return None

    start = c.state().step
    with contactsim.Controller(c, policy, joint_state=True) as ctl:
        c.set_mode("lockstep")
        c.resume()
        ctl.wait_for_step(start + 20, timeout=60)
        c.pause()
        # still registered: what the client holds of the joints is STATE's
        st = c.state()
        assert c.joint_state().step == st.step > start
        q, _, _ = arm.joint_state()
        np.testing.assert_array_equal(q, st.joints.of_model(arm.id)[0])
    remove()
    c.set_mode("free_run")
    in_lockstep = [js for js in heard if start < js.step <= start + 20]
    assert in_lockstep == []
    last = seen[max(seen)]
    assert last.names == IIWA_JOINTS and list(last.model_ids) == [arm.id] * 7
    assert np.all(last.positions != 0.0)


def test_actuator_commands_round_trip_and_refusals_change_nothing(arm_server):
    c = arm_server.client
    arm = c.load_model(IIWA, name="arm", fixed_base=True)
    ids = [arm.joint_id(n) for n in IIWA_JOINTS]
    r = arm.set_joint_targets(np.linspace(-0.3, 0.3, 7), kp=400.0, kd=40.0)
    assert list(r.ids) == ids
    assert list(arm.set_joint_targets(np.zeros(7)).ids) == ids    # keeps the gains
    assert list(arm.set_effort_limits(np.full(7, 100.0)).ids) == ids
    assert list(arm.set_joint_torques(np.ones(7)).ids) == ids
    with pytest.raises(contactsim.CommandError, match=r"has 7 joints with a coordinate, got 6 values"):
        arm.set_joint_targets(np.zeros(6))
    with pytest.raises(contactsim.CommandError, match=r"joints\[3\]\.target_position must be a finite number, got nan"):
        arm.set_joint_targets([0, 0, 0, math.nan, 0, 0, 0])
    with pytest.raises(contactsim.CommandError, match=r"joints\[0\]\.kp must be finite and >= 0"):
        arm.set_joint_targets(np.zeros(7), kp=-1.0)
    with pytest.raises(contactsim.CommandError, match=r"joints\[0\]\.effort_limit must be > 0"):
        arm.set_effort_limits(np.zeros(7))
    with pytest.raises(contactsim.CommandError, match=r"unknown joint id 999"):
        c.set_joint_actuators(joints=[ids[0], 999], kp=[1.0, 1.0])
    _, hinge = _pendulum(c, x=2.0)
    with pytest.raises(contactsim.CommandError, match=r"is not a joint of model"):
        c.set_joint_actuators(joints=[hinge], model=arm, kp=[1.0])
    with pytest.raises(contactsim.CommandError, match=r"unknown model id 77"):
        c.set_joint_actuators(model=77, kp=[1.0])
    assert list(c.set_joint_actuator(hinge, kp=5.0).ids) == [hinge]
    assert list(arm.clear_actuators().ids) == ids
    status = c.wait_for_status(lambda s: s.commands_rejected >= 7, timeout=5)
    assert status.commands_rejected >= 7


def test_lockstep_input_with_a_bad_joint_is_refused_and_the_step_waits(server):
    c = server.client
    _, hinge = _pendulum(c)
    bob = c.add_sphere(0.05, position=(3, 0, 1))
    rod = c.add_joint("distance", bob, None, anchor=(3, 0, 2))
    replies = []
    c.on_reply(lambda r: replies.append(r) if r.code != 0 else None)
    c.register_controller()
    c.set_mode("lockstep")
    c.resume()
    step = c.state().step
    for joints, says in ((contactsim.JointCommand([rod], torque=1.0), "distance"),
                         (contactsim.JointCommand([12345], torque=1.0), "unknown joint id 12345"),
                         (contactsim.JointCommand([hinge], kp=-2.0), "joints[0].kp")):
        n = len(replies)
        c.send_input(step + 1, joints=joints)
        deadline = time.monotonic() + 5
        while len(replies) == n and time.monotonic() < deadline:
            time.sleep(0.05)
        assert len(replies) > n and says in replies[-1].message, [r.message for r in replies]
        assert c.state().step == step
    c.send_input(step + 1, joints=contactsim.JointCommand([hinge], torque=0.5))
    assert c.wait_for_state(lambda s: s.step == step + 1, timeout=10).step == step + 1
    c.pause()
    c.release_controller()


def test_joint_state_read_back_from_a_log_equals_what_was_published(server, tmp_path):
    c = server.client
    _pendulum(c)
    box = c.add_box((0.05, 0.05, 0.05), position=(1, 0, 1.5), mass=1.0)
    slider = c.add_joint("prismatic", box, None, anchor=(1, 0, 1.5), axis=(0, 0, 1), limits=(-0.2, 0.2))
    c.set_joint_actuator(slider, target_position=0.1, kp=100.0, kd=10.0)
    published = {}
    c.on_joint_state(lambda js: published.setdefault(js.step, js))
    path = tmp_path / "joints.lcmlog"
    with LcmRecorder(server.url, server.prefix + "_.*", path) as recorder:
        for _ in range(5):  # in bursts the logger drains (lcm_recorder.py)
            c.step(8)
            recorder.sync()
    log = read_log(path)
    j = log.joints
    assert list(j.joint_ids) == [1, slider] and j.names == ["1", str(slider)]
    assert len(j.step) > 0
    for n, step in enumerate(j.step):
        js = published[int(step)]
        assert j.time[n] == js.time
        np.testing.assert_array_equal(j.position[n], js.positions)
        np.testing.assert_array_equal(j.velocity[n], js.velocities)
        np.testing.assert_array_equal(j.effort[n], js.efforts)
    from contactsim.plot import plot_joints
    png = plot_joints(j, str(tmp_path))
    with open(png, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"


def _ctl(server, *args):
    return subprocess.run([str(CTL), "--lcm-url", server.url, "--prefix", server.prefix, *args],
                          capture_output=True, text=True, timeout=30)


def test_both_command_lines_set_and_read_joints(server):
    if not CTL.exists():
        pytest.skip("%s is not built" % CTL)
    c = server.client
    _, hinge = _pendulum(c)
    c.step(3)
    r = cli(server, "joint", "set", str(hinge), "--kp", "20", "--target-position", "0.1")
    assert r.returncode == 0, r.stdout + r.stderr
    r = _ctl(server, "joint", "set", str(hinge), "--kd", "2")
    assert r.returncode == 0, r.stdout + r.stderr
    r = cli(server, "joint", "set", str(hinge), "--kp", "-1")
    assert r.returncode == 1 and "joints[0].kp" in r.stderr, r.stdout + r.stderr
    r = _ctl(server, "joint", "set", "999", "--kp", "1")
    assert r.returncode == 1 and "unknown joint id 999" in r.stderr, r.stdout + r.stderr
    py = cli(server, "joint", "state")
    cpp = _ctl(server, "joint", "state")
    assert py.returncode == 0 and cpp.returncode == 0, py.stderr + cpp.stderr
    assert py.stdout == cpp.stdout
    assert py.stdout.startswith("joint %d model 0 %d position " % (hinge, hinge))
    assert cli(server, "joint", "clear", str(hinge)).returncode == 0
    assert _ctl(server, "joint", "clear", str(hinge)).returncode == 0


# ---------------------------------------------------------------- physics
def test_position_actuator_holds_a_pendulum(server):
    """A 1 kg bob 0.5 m out on a horizontal hinge, held at 0 by kp = 2000 N m/rad:
    it settles where kp q = m g L cos q, q ~ -2.45e-3 rad."""
    c = server.client
    need_actuators(c)
    bob = c.add_sphere(0.05, position=(0.5, 0, 2), mass=1.0)
    hinge = c.add_joint("hinge", bob, None, anchor=(0, 0, 2), axis=(0, 1, 0))
    kp, m, g, L = 2000.0, 1.0, 9.81, 0.5
    c.set_joint_actuator(hinge, target_position=0.0, kp=kp, kd=60.0)
    c.step(480)
    q, v, u = c.request_joint_state().of_joints([hinge])
    # the bob hangs below the anchor's height: rotation about +y moves +x down for q > 0
    q_eq = m * g * L / kp
    assert abs(abs(q[0]) - q_eq) < 0.05 * q_eq, q
    assert abs(v[0]) < 1e-3
    assert abs(abs(u[0]) - m * g * L) < 0.05 * m * g * L


def test_lockstep_joint_command_acts_for_exactly_one_step(server):
    """A 0.5 N m torque on a free hinge for step k only: the rate jumps by
    tau dt / I at step k and stays; the effort is tau at k and 0 after."""
    c = server.client
    need_actuators(c)
    c.set_gravity((0, 0, 0))
    ball = c.add_sphere(0.1, position=(0, 0, 2), mass=2.0)
    hinge = c.add_joint("hinge", ball, None, anchor=(0, 0, 2), axis=(0, 0, 1))
    inertia = 0.4 * 2.0 * 0.1 ** 2
    k = c.state().step + 3
    seen = {}

    def policy(state, joints):
        seen[joints.step] = joints
        return contactsim.JointCommand([hinge], torque=0.5) if state.step + 1 == k else None

    with contactsim.Controller(c, policy, joint_state=True) as ctl:
        c.set_mode("lockstep")
        c.resume()
        ctl.wait_for_step(k + 3, timeout=30)
        c.pause()
    dt = 1.0 / 240.0
    assert seen[k - 1].velocities[0] == 0.0 and seen[k - 1].efforts[0] == 0.0
    assert seen[k].efforts[0] == 0.5
    for step in (k, k + 1, k + 2, k + 3):
        assert seen[step].velocities[0] == pytest.approx(0.5 * dt / inertia, rel=1e-6), step
    for step in (k + 1, k + 2, k + 3):
        assert seen[step].efforts[0] == 0.0, step


def test_joint_state_positions_are_the_models_configuration(arm_server):
    """The iiwa's links put where pinocchio's kinematics say for a
    configuration q: JOINT_STATE reads q back, in the file's joint order."""
    pin = pytest.importorskip("pinocchio")
    c = arm_server.client
    arm = c.load_model(IIWA, name="arm", fixed_base=True)
    model = pin.buildModelFromUrdf(IIWA)
    data = model.createData()
    q = np.array([0.3, 0.8, -0.4, -1.2, 0.5, 0.7, -0.3])
    pin.framesForwardKinematics(model, data, q)
    poses = {f.name: (data.oMf[i].translation.copy(), data.oMf[i].rotation.copy())
             for i, f in enumerate(model.frames) if f.type == pin.FrameType.BODY}
    arm.set_link_poses(poses)
    np.testing.assert_allclose(c.request_joint_state().of_model(arm.id)[0], q, atol=1e-9)


def test_iiwa_tracks_a_joint_trajectory_at_1khz_in_lockstep(arm_server):
    """A Python controller answers each STATE with the next step's targets
    (q_d, qdot_d) and pinocchio's inverse dynamics at them as feed-forward
    torque, over standing gains: the RMS error of the seven joints along
    q_d(t) = A (1 - cos(2 pi t)) / 2 stays below 1 mrad over 0.5 s at 1 kHz."""
    pin = pytest.importorskip("pinocchio")
    c = arm_server.client
    need_actuators(c)
    dt = 1e-3
    c.set_timestep(dt)
    arm = c.load_model(IIWA, name="arm", fixed_base=True)
    model = pin.buildModelFromUrdf(IIWA)
    data = model.createData()
    amplitude = np.array([0.4, 0.3, -0.3, -0.5, 0.3, 0.4, 0.5])
    w = 2.0 * math.pi

    def reference(t):
        return (amplitude * (1 - math.cos(w * t)) / 2, amplitude * w * math.sin(w * t) / 2,
                amplitude * w * w * math.cos(w * t) / 2)

    arm.set_joint_targets(np.zeros(7), kp=2e4, kd=400.0)
    errors, start = [], []

    def policy(state, joints):
        if not start:
            start.append(state.step)
        t_now = (state.step - start[0]) * dt
        errors.append(joints.of_model(arm.id)[0] - reference(t_now)[0])
        q, v, a = reference(t_now + dt)
        return arm.joint_command(target_position=q, target_velocity=v, torque=pin.rnea(model, data, q, v, a))

    with contactsim.Controller(c, policy, joint_state=True) as ctl:
        c.set_mode("lockstep")
        c.resume()
        ctl.wait_for_step(c.state().step + 500, timeout=300)
        c.pause()
    e = np.array(errors)
    assert len(e) >= 500
    rms = float(np.sqrt(np.mean(e ** 2)))
    print("\niiwa at 1 kHz: RMS tracking error %.3g rad, worst %.3g rad" % (rms, np.abs(e).max()))
    assert rms < 1e-3


def test_gym_arm_task_observes_joints_and_acts_through_them(arm_server):
    gym = pytest.importorskip("contactsim.gym", reason="gymnasium is not importable: contactsim.gym needs it")
    for control in ("torque", "position"):
        env = gym.ContactsimEnv(arm_server.client, gym.ArmTask(IIWA, np.full(7, 0.2), control=control, max_steps=3))
        obs, info = env.reset(seed=1)
        assert env.observation_space.shape == obs.shape == (14,)
        assert env.action_space.shape == (7,)
        np.testing.assert_allclose(obs[:7], 0.0, atol=1e-9)   # the arm loads at q = 0
        for k in range(3):
            obs, reward, terminated, truncated, info = env.step(np.full(7, 0.5))
            assert obs.shape == (14,) and np.isfinite(reward) and not terminated
            assert truncated == (k == 2)
        env.close()
