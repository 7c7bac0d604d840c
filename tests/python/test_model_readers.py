"""Checks the URDF reader against peers on robot files no one here wrote.

contactsim-model-info (tools/model_info) prints what the reader makes of a
file; every URDF in PyBullet's pybullet_data is read and compared with

* PyBullet (p.DIRECT, loadURDF with URDF_USE_INERTIA_FROM_FILE so that it
  keeps the file's inertia instead of computing one from the collision
  shapes): link and joint names and counts, joint types, and each link's
  mass, centre of mass (the inertial frame's position in the link frame) and
  inertia. PyBullet diagonalises the tensor: it reports the principal
  moments, compared with the description's eigenvalues to 1e-9 relative,
  and the principal frame's orientation, compared through the tensor both
  give in the link frame, R diag(I) R^T, to 1e-6 relative: PyBullet's
  Jacobi iteration (btMatrix3x3::diagonalize, threshold 1e-6, in its URDF
  importer) stops with off-diagonal terms of up to that size left over
  (4.5e-8 measured, aliengo's upper legs). A link's <contact>
  <inertia_scaling> (a PyBullet extension the reader ignores) scales
  PyBullet's moments and is divided out;
* pinocchio (pin.buildModelFromUrdf): the world pose of every link under the
  description's forward kinematics (service/model/model_kinematics.h, the
  tool's --fk) over 100 random joint configurations, to 1e-9 m and rad.

A file the reader refuses must be one of EXPECTED_REFUSALS, with the reason
its message gives; each is a file that breaks URDF or physics (PyBullet,
which reads leniently, loads most of them anyway, and warns about the bad
inertias itself).

pybullet_data's SDF files: the one the SDF reader takes (kuka_iiwa/model.sdf)
is compared at the zero configuration with the file's own <pose>s, composed
here, and over random configurations with PyBullet's loadSDF; the others
are in EXPECTED_SDF_REFUSALS.
"""
import functools
import json
import os
import xml.etree.ElementTree as ET
import subprocess
from pathlib import Path

import numpy as np
import pytest

pybullet = pytest.importorskip("pybullet")
pybullet_data = pytest.importorskip("pybullet_data")
pin = pytest.importorskip("pinocchio")

BUILD = Path(os.environ.get("CONTACTSIM_BUILD_DIR") or Path(__file__).resolve().parents[2] / "build")
TOOL = BUILD / "bin" / "contactsim-model-info"
DATA = Path(pybullet_data.getDataPath())
# pybullet_data's 1000 generated blobs (random_urdfs/) all have izz = 0 and
# are refused as not positive definite; two stand for them.
URDFS = sorted(str(p.relative_to(DATA)) for p in DATA.rglob("*.urdf") if "random_urdfs" not in p.parts)
URDFS += ["random_urdfs/000/000.urdf", "random_urdfs/999/999.urdf"]

# file -> a piece of the refusal's message (why the file is refused)
EXPECTED_REFUSALS = {
    # principal moments breaking I1 + I2 >= I3 by 0.7 to 4 % (PyBullet: "Bad
    # inertia tensor properties, setting inertia to zero")
    "TwoJointRobot_w_fixedJoints.urdf": "triangle inequality",
    "TwoJointRobot_wo_fixedJoints.urdf": "triangle inequality",
    "mini_cheetah/mini_cheetah.urdf": "triangle inequality",
    "xarm/link2.urdf": "triangle inequality",
    "xarm/link2_com.urdf": "triangle inequality",
    "xarm/link3.urdf": "triangle inequality",
    "xarm/link3_com.urdf": "triangle inequality",
    "xarm/xarm6_robot.urdf": "triangle inequality",
    "xarm/xarm6_robot_white.urdf": "triangle inequality",
    "xarm/xarm6_with_gripper.urdf": "triangle inequality",
    # a 13.7 kg chassis with a zero inertia
    "laikago/laikago.urdf": "not positive definite",
    "laikago/laikago_toes.urdf": "not positive definite",
    "laikago/laikago_toes_limits.urdf": "not positive definite",
    "random_urdfs/000/000.urdf": "not positive definite",
    "random_urdfs/999/999.urdf": "not positive definite",
    # numbers that are not numbers: "0.07,", "-1.57.", an unexpanded xacro
    # "$(optenv ...)", four numbers for a vector of three
    "bicycle/bike.urdf": "Unable to parse component [0.07,]",
    "biped/biped2d_pybullet.urdf": "(-1.57.) is not a valid float",
    "husky/husky.urdf": "$(optenv",
    "quadruped/microtaur/microtaur.urdf": "Parser found 4 elements but 3 expected",
    "racecar/racecar_differential.urdf": "Parser found 4 elements but 3 expected",
    # PyBullet's own extensions: a spherical joint, plane and cdf geometry
    "humanoid/humanoid.urdf": "unknown joint type 'spherical'",
    "spherical_joint_limit.urdf": "unknown joint type 'spherical'",
    "plane_implicit.urdf": "Unknown geometry type 'plane'",
    "toys/concave_box.urdf": "Unknown geometry type 'cdf'",
    # PyBullet reads lower > upper as "no limit"; URDF gives it no meaning
    "cube_no_rotation.urdf": "lower 1 is above upper -1",
    # mesh files that are not where the file says
    "differential/diff_ring.urdf": "cannot find 'differential/diff_ring.stl'",
    "kuka_iiwa/model_for_sdf.urdf": "cannot find 'meshes/coarse/link_0.stl'",
    # a deformable body (<deformable>), no links
    "torus_deform.urdf": "the model has no links",
}

# The description's numbers are urdfdom's doubles; PyBullet's pass through
# its own parser, pinocchio's through its parser and its rpy and joint
# maths: the bound is 1e-9, and the principal frame PyBullet's diagonalise
# leaves off by up to its threshold (module docstring).
REL_TOL = 1e-9
BULLET_JACOBI_TOL = 1e-6
FK_TOL = 1e-9


@functools.lru_cache(maxsize=None)
def model_info_once(rel):
    """The tool's reading of a file, once per file for all the tests."""
    return model_info(rel)


def model_info(rel, stdin=None):
    args = [str(TOOL), str(DATA / rel), "--no-env"] + (["--fk"] if stdin is not None else [])
    return subprocess.run(args, input=stdin, capture_output=True, text=True, timeout=120)


@pytest.fixture(scope="module")
def bullet():
    client = pybullet.connect(pybullet.DIRECT)
    yield client
    pybullet.disconnect(client)


def quat_matrix(wxyz):
    w, x, y, z = wxyz
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def bullet_links(client, rel, fixed):
    """name -> getDynamicsInfo, and the joints as (name, type, child link)."""
    body = pybullet.loadURDF(str(DATA / rel), useFixedBase=fixed, flags=pybullet.URDF_USE_INERTIA_FROM_FILE,
                             physicsClientId=client)
    links = {pybullet.getBodyInfo(body, physicsClientId=client)[0].decode():
             pybullet.getDynamicsInfo(body, -1, physicsClientId=client)}
    joints = []
    for i in range(pybullet.getNumJoints(body, physicsClientId=client)):
        info = pybullet.getJointInfo(body, i, physicsClientId=client)
        links[info[12].decode()] = pybullet.getDynamicsInfo(body, i, physicsClientId=client)
        joints.append((info[1].decode(), info[2], info[12].decode()))
    pybullet.removeBody(body, physicsClientId=client)
    return links, joints


BULLET_JOINT_TYPE = {"revolute": pybullet.JOINT_REVOLUTE, "continuous": pybullet.JOINT_REVOLUTE,
                     "prismatic": pybullet.JOINT_PRISMATIC, "fixed": pybullet.JOINT_FIXED,
                     "planar": pybullet.JOINT_PLANAR}


def inertia_scaling(rel):
    """link name -> PyBullet's <contact><inertia_scaling> of that link."""
    out = {}
    for link in ET.parse(DATA / rel).getroot().iter("link"):
        scaling = link.find("contact/inertia_scaling")
        if scaling is not None:
            out[link.get("name")] = float(scaling.get("value"))
    return out


def read(rel):
    out = model_info_once(rel)
    if rel in EXPECTED_REFUSALS:
        assert out.returncode == 1, f"{rel} was expected to be refused"
        assert EXPECTED_REFUSALS[rel] in out.stderr, out.stderr
        assert rel.split("/")[-1] in out.stderr, "the message names the file"
        pytest.skip(f"refused as expected: {out.stderr.strip()[:200]}")
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


@pytest.mark.parametrize("rel", URDFS)
def test_names_counts_and_mass_properties_match_pybullet(bullet, rel):
    desc = read(rel)
    # a fixed base reports mass 0: the base's numbers come from a free load
    links, joints = bullet_links(bullet, rel, fixed=True)
    free_links, _ = bullet_links(bullet, rel, fixed=False)
    links[desc["root_link"]] = free_links[desc["root_link"]]
    assert sorted(links) == sorted(l["name"] for l in desc["links"])
    by_name = {j["name"]: j for j in desc["joints"]}
    assert sorted(by_name) == sorted(j[0] for j in joints)
    for name, bullet_type, child in joints:
        assert by_name[name]["child"] == child
        if by_name[name]["type"] in BULLET_JOINT_TYPE:
            assert BULLET_JOINT_TYPE[by_name[name]["type"]] == bullet_type, name
    scaling = inertia_scaling(rel)
    inertials = {l.get("name") for l in ET.parse(DATA / rel).getroot().iter("link") if l.find("inertial") is not None}
    for link in desc["links"]:
        info = links[link["name"]]
        mass, moments, com, orn = info[0], np.array(info[2]), np.array(info[3]), info[4]
        moments = moments / scaling.get(link["name"], 1.0)
        if link["massless"]:
            # an explicit mass of 0 PyBullet keeps; without <inertial> a root
            # gets mass 0 (a static base) and any other link 1 kg with a unit
            # inertia, PyBullet's defaults
            if link["name"] in inertials or link["name"] == desc["root_link"]:
                assert mass == 0.0, link["name"]
            else:
                assert mass == 1.0 and list(moments) == [1.0, 1.0, 1.0], (link["name"], mass, moments)
            continue
        assert abs(mass - link["mass"]) <= REL_TOL * link["mass"], link["name"]
        origin = link["inertial_origin"]
        assert np.allclose(com, origin["position"], rtol=0, atol=REL_TOL * max(1.0, np.abs(com).max())), link["name"]
        r_origin = quat_matrix(origin["orientation"])
        ours = r_origin @ np.array(link["inertia"]) @ r_origin.T
        r_bullet = quat_matrix((orn[3], orn[0], orn[1], orn[2]))
        theirs = r_bullet @ np.diag(moments) @ r_bullet.T
        scale = np.abs(ours).max()
        assert np.abs(np.sort(np.linalg.eigvalsh(ours)) - np.sort(moments)).max() <= REL_TOL * scale, link["name"]
        assert np.abs(ours - theirs).max() <= BULLET_JACOBI_TOL * scale, (link["name"], ours, theirs)


def pin_configuration(model, desc, q_desc):
    """pinocchio's q for the description's coordinates (joint order)."""
    q = pin.neutral(model)
    at = 0
    for j in desc["joints"]:
        n = j["coordinates"]
        values = q_desc[at:at + n]
        at += n
        if n == 0:
            continue
        jm = model.joints[model.getJointId(j["name"])]
        i = jm.idx_q
        if j["type"] == "continuous":
            q[i:i + 2] = [np.cos(values[0]), np.sin(values[0])]
        elif j["type"] == "floating":
            x, y, z, qw, qx, qy, qz = values
            q[i:i + 7] = [x, y, z, qx, qy, qz, qw]
        else:
            q[i] = values[0]
    return q


def random_configuration(desc, rng):
    q = []
    for j in desc["joints"]:
        if j["type"] in ("revolute", "prismatic"):
            lim = j["limits"]
            q.append(rng.uniform(lim["lower"], lim["upper"]))
        elif j["type"] == "continuous":
            q.append(rng.uniform(-np.pi, np.pi))
        elif j["type"] == "floating":
            quat = rng.normal(size=4)
            q += list(rng.uniform(-1, 1, 3)) + list(quat / np.linalg.norm(quat))
    return q


@pytest.mark.parametrize("rel", URDFS)
def test_forward_kinematics_matches_pinocchio(rel):
    desc = read(rel)
    if any(j["type"] == "planar" for j in desc["joints"]):
        pytest.skip("pinocchio's planar joint takes (x, y, cos, sin) in its own plane")
    rng = np.random.default_rng(7)
    configurations = [random_configuration(desc, rng) for _ in range(100)]
    out = model_info(rel, stdin="".join(" ".join(repr(v) for v in q) + "\n" for q in configurations))
    assert out.returncode == 0, out.stderr
    fk = json.loads(out.stdout)["fk"]
    model = pin.buildModelFromUrdf(str(DATA / rel))
    data = model.createData()
    worst = 0.0
    for q_desc, poses in zip(configurations, fk):
        q = pin_configuration(model, desc, q_desc)
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacements(model, data)
        for pose in poses:
            oMf = data.oMf[model.getFrameId(pose["link"], pin.BODY)]
            dp = np.abs(oMf.translation - pose["position"]).max()
            dr = np.linalg.norm(pin.log3(oMf.rotation.T @ quat_matrix(pose["orientation"])))
            worst = max(worst, dp, dr)
    assert worst <= FK_TOL, f"{rel}: worst difference {worst:.3g} m or rad"


# pybullet_data's SDF files: the one the reader takes is compared with
# PyBullet's loadSDF; the others are refused for these reasons.
SDFS = sorted(str(p.relative_to(DATA)) for p in DATA.rglob("*.sdf"))
EXPECTED_SDF_REFUSALS = {
    # a link named "world", which SDF reserves
    "gripper/wsg50_one_motor_gripper.sdf": "[world] is reserved",
    "gripper/wsg50_one_motor_gripper_free_base.sdf": "[world] is reserved",
    "gripper/wsg50_one_motor_gripper_new.sdf": "[world] is reserved",
    "gripper/wsg50_one_motor_gripper_new_free_base.sdf": "[world] is reserved",
    "gripper/wsg50_one_motor_gripper_no_finger.sdf": "[world] is reserved",
    "gripper/wsg50_with_r2d2_gripper.sdf": "[world] is reserved",
    # two collisions of one name in a link; two models of one name
    "kiva_shelf/model.sdf": "collision with name[pod_collision] already exists",
    "kuka_iiwa/model2.sdf": "model with name[lbr_iiwa] already exists",
    # mesh URIs "/meshes/..." that are not absolute paths on any machine
    "kuka_iiwa/kuka_with_gripper.sdf": "cannot find '/meshes/link_0.stl'",
    "kuka_iiwa/kuka_with_gripper2.sdf": "cannot find '/meshes/link_0.stl'",
    # a fixed joint to the world
    "kuka_iiwa/kuka_world.sdf": "a joint to the world is not read",
    # a ground plane; worlds of several models
    "plane_stadium.sdf": "is not read: box, sphere, cylinder, capsule and mesh are",
    "stadium.sdf": "the world holds 3 models",
    "stadium_no_collision.sdf": "the world holds 3 models",
}


def read_sdf(rel):
    out = model_info_once(rel)
    if rel in EXPECTED_SDF_REFUSALS:
        assert out.returncode == 1, f"{rel} was expected to be refused"
        assert EXPECTED_SDF_REFUSALS[rel] in out.stderr, out.stderr
        pytest.skip(f"refused as expected: {out.stderr.strip()[:200]}")
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def pose_matrix(position, wxyz):
    m = np.eye(4)
    m[:3, :3] = quat_matrix(wxyz)
    m[:3, 3] = position
    return m


def rpy_matrix(roll, pitch, yaw):
    """SDF's and URDF's rpy: about fixed x, then y, then z."""
    def about(axis, angle):
        c, s = np.cos(angle), np.sin(angle)
        i, j = [k for k in range(3) if k != axis]
        m = np.eye(3)
        m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
        return m
    return about(2, yaw) @ about(1, pitch) @ about(0, roll)


def sdf_link_poses(path):
    """Each link's <pose> (in the model frame, as pybullet_data's SDF 1.6
    files give them) as a 4x4 matrix, computed here from the file's text."""
    out = {}
    for link in ET.parse(path).getroot().iter("link"):
        v = [float(x) for x in link.find("pose").text.split()]
        m = np.eye(4)
        m[:3, :3] = rpy_matrix(*v[3:])
        m[:3, 3] = v[:3]
        out[link.get("name")] = m
    return out


def bullet_link_frames(client, body, index):
    """name -> each link's frame relative to the root link's frame."""
    com_offset = pybullet.getDynamicsInfo(body, -1, physicsClientId=client)[3:5]
    pos, orn = pybullet.getBasePositionAndOrientation(body, physicsClientId=client)
    # the root's link frame: its centre-of-mass frame less the inertial offset
    root = pose_matrix(pos, (orn[3], *orn[:3])) @ np.linalg.inv(
        pose_matrix(com_offset[0], (com_offset[1][3], *com_offset[1][:3])))
    frames = {}
    for name, i in index.items():
        if i >= 0:
            state = pybullet.getLinkState(body, i, computeForwardKinematics=True, physicsClientId=client)
            frames[name] = np.linalg.inv(root) @ pose_matrix(state[4], (state[5][3], *state[5][:3]))
    return frames


# PyBullet's SDF importer places kuka_iiwa/model.sdf's links 2.4e-7 away from
# where the file's own numbers put them at the zero configuration (measured:
# the description agrees with the file to 4.4e-16, see the zero test below),
# a rounding in its parse that the joint motions carry to 6.4e-7 over random
# configurations.
BULLET_SDF_TOL = 1e-6


@pytest.mark.parametrize("rel", SDFS)
def test_sdf_zero_configuration_matches_the_files_poses(rel):
    """At q = 0 every link's frame relative to the root is the file's own
    <pose>s composed, computed here independently of libsdformat."""
    desc = read_sdf(rel)
    out = model_info(rel, stdin=" ".join("0" for _ in range(sum(j["coordinates"] for j in desc["joints"]))) + "\n")
    poses = json.loads(out.stdout)["fk"][0]
    links = sdf_link_poses(DATA / rel)
    root = np.linalg.inv(links[desc["root_link"]])
    worst = max(np.abs(root @ links[p["link"]] - pose_matrix(p["position"], p["orientation"])).max() for p in poses)
    assert worst <= FK_TOL, f"{rel}: worst difference {worst:.3g}"


@pytest.mark.parametrize("rel", SDFS)
def test_sdf_masses_and_forward_kinematics_match_pybullet(bullet, rel):
    """PyBullet's loadSDF computes inertias from the collision shapes, so
    masses and centres of mass are compared, and each link's frame relative
    to the root's, after resetJointState, with the description's forward
    kinematics over 100 random configurations."""
    desc = read_sdf(rel)
    (body,) = pybullet.loadSDF(str(DATA / rel), physicsClientId=bullet)
    n = pybullet.getNumJoints(body, physicsClientId=bullet)
    index = {pybullet.getJointInfo(body, i, physicsClientId=bullet)[12].decode(): i for i in range(n)}
    index[pybullet.getBodyInfo(body, physicsClientId=bullet)[0].decode()] = -1
    assert sorted(index) == sorted(l["name"] for l in desc["links"])
    for link in desc["links"]:
        info = pybullet.getDynamicsInfo(body, index[link["name"]], physicsClientId=bullet)
        if not link["massless"] and index[link["name"]] >= 0:
            assert abs(info[0] - link["mass"]) <= REL_TOL * link["mass"]
            assert np.allclose(info[3], link["inertial_origin"]["position"], rtol=0, atol=REL_TOL)
    rng = np.random.default_rng(11)
    configurations = [random_configuration(desc, rng) for _ in range(100)]
    out = model_info(rel, stdin="".join(" ".join(repr(v) for v in q) + "\n" for q in configurations))
    fk = json.loads(out.stdout)["fk"]
    moving = [j for j in desc["joints"] if j["coordinates"] == 1]
    worst = 0.0
    for q, poses in zip(configurations, fk):
        for j, value in zip(moving, q):
            pybullet.resetJointState(body, index[j["child"]], value, physicsClientId=bullet)
        frames = bullet_link_frames(bullet, body, index)
        for pose in poses:
            if pose["link"] in frames:
                ours = pose_matrix(pose["position"], pose["orientation"])
                worst = max(worst, np.abs(frames[pose["link"]] - ours).max())
    pybullet.removeBody(body, physicsClientId=bullet)
    assert worst <= BULLET_SDF_TOL, f"{rel}: worst difference {worst:.3g}"
