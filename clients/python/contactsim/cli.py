"""contactsim-py: one command to a running contactsim server.

    contactsim-py [--lcm-url URL] [--prefix P] [--timeout S] [--auth-key-file FILE] COMMAND ...
      status | add sphere R [opts] | add box HX HY HZ [opts] | add plane NX NY NZ OFFSET | add mesh PATH [--scale S]
      | add heightfield PATH [--spacing DX DY] [--rows R --cols C] [--scale S] [--offset O]
      remove ID | joint add KIND A B --anchor X Y Z [opts] | joint remove ID
      joint state | joint set ID [--torque T] [--target-position Q] [--kp KP] [--kd KD] [...] | joint clear ID
      model load PATH [--name N] [--position X Y Z] [--orientation W X Y Z] [--fixed-base] [--self-collide]
                 [--max-hull-vertices N]
      model remove ID | model list
      method NAME [key=value ...] | pause | resume | step [N] | reset
      compare METHOD[:key=value,...] ... [--steps N] [--workers W] [--address A] [--plot FILE] [--csv FILE]

The subcommands are contactsim-ctl's (the C++ CLI), so either serves a script;
compare (a fleet of servers, docs/fleet.md) is the Python client's alone.

Exit status: 0 OK, 1 error reply, 2 no reply (timeout) or an unusable auth key file.
"""
import argparse
import os
import sys

from .client import Client
from .errors import AuthKeyError, CommandError, TimeoutError
from .joints import KINDS


def _parser():
    p = argparse.ArgumentParser(prog="contactsim-py", description=__doc__.split("\n")[0])
    p.add_argument("--lcm-url", default=None, help="LCM URL (default: $LCM_DEFAULT_URL or project default)")
    p.add_argument("--prefix", default="CONTACTSIM", help="channel prefix")
    p.add_argument("--timeout", type=float, default=2.0, help="reply timeout, s")
    p.add_argument("--auth-key-file", default=None, metavar="FILE",
                   help="sign commands and check the server's signatures with this key "
                        "(default: $CONTACTSIM_AUTH_KEY_FILE; docs/protocol.md, Authentication)")
    sub = p.add_subparsers(dest="cmd", required=True)
    sub.add_parser("status", help="print the latest STATUS")
    add = sub.add_parser("add", help="add a body").add_subparsers(dest="shape", required=True)
    for shape, sizes in (("sphere", ["radius"]), ("box", ["hx", "hy", "hz"])):
        a = add.add_parser(shape)
        for s in sizes:
            a.add_argument(s, type=float)
        a.add_argument("--position", type=float, nargs=3, default=(0, 0, 0), metavar=("X", "Y", "Z"))
        a.add_argument("--velocity", type=float, nargs=3, default=(0, 0, 0), metavar=("VX", "VY", "VZ"))
        a.add_argument("--mass", type=float)
        a.add_argument("--density", type=float)
        a.add_argument("--restitution", type=float)
        a.add_argument("--friction", type=float)
        a.add_argument("--fixed", action="store_true")
        a.add_argument("--name", default="")
    a = add.add_parser("mesh", help="a static triangle mesh from a file the server reads (OBJ, STL, PLY, DAE)")
    a.add_argument("path")
    a.add_argument("--scale", type=float, default=1.0)
    a.add_argument("--position", type=float, nargs=3, default=(0, 0, 0), metavar=("X", "Y", "Z"))
    a.add_argument("--restitution", type=float)
    a.add_argument("--friction", type=float)
    a.add_argument("--name", default="")
    a = add.add_parser("heightfield", help="a static heightfield from a height map the server reads "
                                           "(16-bit greyscale PNG, or raw little-endian uint16 with --rows --cols)")
    a.add_argument("path")
    a.add_argument("--spacing", type=float, nargs=2, default=(1.0, 1.0), metavar=("DX", "DY"), help="m")
    a.add_argument("--rows", type=int, default=0, help="a raw file's rows (along y)")
    a.add_argument("--cols", type=int, default=0, help="a raw file's columns (along x)")
    a.add_argument("--scale", type=float, default=1.0, help="m at the largest sample, 65535")
    a.add_argument("--offset", type=float, default=0.0, help="m at sample 0")
    a.add_argument("--position", type=float, nargs=3, default=(0, 0, 0), metavar=("X", "Y", "Z"))
    a.add_argument("--restitution", type=float)
    a.add_argument("--friction", type=float)
    a.add_argument("--name", default="")
    a = add.add_parser("plane")
    for s in ("nx", "ny", "nz", "offset"):
        a.add_argument(s, type=float)
    a.add_argument("--restitution", type=float)
    a.add_argument("--friction", type=float)
    sub.add_parser("remove").add_argument("id", type=int)
    _joint_parser(sub)
    _model_parser(sub)
    m = sub.add_parser("method", help="switch the contact method")
    m.add_argument("name")
    m.add_argument("params", nargs="*", metavar="key=value")
    for name in ("pause", "resume", "reset"):
        sub.add_parser(name)
    st = sub.add_parser("step", help="take N steps; a progress bar on a terminal")
    st.add_argument("n", type=int, nargs="?", default=1)
    st.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                    help="draw a progress bar (default: when stderr is a terminal)")
    cmp = sub.add_parser("compare", help="fork the world and run it under each method on a fleet (docs/fleet.md)")
    cmp.add_argument("methods", nargs="+", metavar="METHOD[:key=value,...]")
    cmp.add_argument("--steps", type=int, default=240)
    cmp.add_argument("--workers", type=int, default=None, help="local Ray workers (default: one per method, at "
                                                                "most one per CPU)")
    cmp.add_argument("--address", default=None, help="a Ray cluster's address instead of a local Ray")
    cmp.add_argument("--plot", default=None, metavar="FILE", help="draw each method's departure into FILE")
    cmp.add_argument("--csv", default=None, metavar="FILE", help="write the table as CSV")
    return p


def _joint_parser(sub):
    """joint add KIND BODY_A [BODY_B] --anchor X Y Z [...] | joint remove ID, as contactsim-ctl."""
    j = sub.add_parser("joint", help="add or remove a joint").add_subparsers(dest="joint_cmd", required=True)
    a = j.add_parser("add", help="add a joint; prints its id")
    a.add_argument("kind", type=str.lower, choices=sorted(KINDS))
    a.add_argument("body_a", type=int)
    a.add_argument("body_b", type=int, nargs="?", default=0, help="body id, or 0 for the world")
    a.add_argument("--anchor", "-a", type=float, nargs=3, required=True, metavar=("X", "Y", "Z"),
                   help="m, world: the joint point (distance: the point on body_b)")
    a.add_argument("--axis", type=float, nargs=3, metavar=("X", "Y", "Z"), help="world, hinge and prismatic")
    a.add_argument("--length", "-l", type=float, help="m, distance only (default: current)")
    a.add_argument("--limits", type=float, nargs=2, metavar=("LOWER", "UPPER"),
                   help="hinge (rad) and prismatic (m)")
    a.add_argument("--damping", type=float, help="N m s/rad (hinge) or N s/m (prismatic)")
    a.add_argument("--friction", type=float, help="N m (hinge) or N (prismatic), Coulomb")
    j.add_parser("remove", help="remove a joint").add_argument("id", type=int)
    j.add_parser("state", help="print every hinge and prismatic joint's position, velocity and effort")
    s = j.add_parser("set", help="set fields of a joint's standing actuator; the others stay")
    s.add_argument("id", type=int)
    for flag, unit in (("torque", "N m or N, feed-forward"), ("target-position", "rad or m (acts while kp > 0)"),
                       ("target-velocity", "rad/s or m/s (acts while kd > 0)"), ("kp", "N m/rad or N/m, >= 0"),
                       ("kd", "N m s/rad or N s/m, >= 0"), ("effort-limit", "N m or N, > 0"),
                       ("velocity-limit", "rad/s or m/s, > 0")):
        s.add_argument("--" + flag, type=float, help=unit)
    j.add_parser("clear", help="remove a joint's actuator").add_argument("id", type=int)
    r = sub.add_parser("ray", help="cast one ray; prints what it hits (docs/protocol.md, Ray casts)")
    r.add_argument("origin", type=float, nargs=3, help="m, world")
    r.add_argument("direction", type=float, nargs=3, help="world, any length")
    r.add_argument("--max-distance", type=float, default=100.0, help="m")
    r.add_argument("--ignore", type=int, nargs="*", default=[], help="body ids the ray passes through")
    sn = sub.add_parser("sensor", help="add a contact sensor or remove a sensor").add_subparsers(
        dest="sensor_cmd", required=True)
    sc = sn.add_parser("contact", help="the contact wrench a body receives each step, on SENSORS")
    sc.add_argument("body", type=int)
    sc.add_argument("name")
    sn.add_parser("remove", help="remove a sensor").add_argument("name")


def _model_parser(sub):
    """model load PATH [...] | model remove ID | model list, as contactsim-ctl (docs/models.md)."""
    m = sub.add_parser("model", help="load, remove or list robot models").add_subparsers(
        dest="model_cmd", required=True)
    a = m.add_parser("load", help="load a URDF or SDF model; prints its links and joints with their ids")
    a.add_argument("path", help="model file (on the server's host, or found among its model paths)")
    a.add_argument("--name", default="", help="the model's name in the world (default: the file's)")
    a.add_argument("--position", type=float, nargs=3, default=(0, 0, 0), metavar=("X", "Y", "Z"),
                   help="m, world: the root link's origin")
    a.add_argument("--orientation", type=float, nargs=4, default=(1, 0, 0, 0), metavar=("W", "X", "Y", "Z"),
                   help="the root link's orientation")
    a.add_argument("--fixed-base", action="store_true", help="the root link is static")
    a.add_argument("--self-collide", action="store_true", help="the model's links collide with each other")
    a.add_argument("--max-hull-vertices", type=int, default=0,
                   help="each collision mesh's hull keeps at most N vertices (0: the server's default, 64; -1: all)")
    m.add_parser("remove", help="remove a model with its bodies and joints").add_argument("id", type=int)
    m.add_parser("list", help="list the loaded models")


def _print_model(model):
    print("model %d %s (%s)" % (model.id, model.name, model.source))
    for link in model.links:
        print("  link %-32s body %d" % (link, model.body_id(link)))
    for joint in model.joints:
        print("  joint %-31s %-10s id %d" % (joint, model.joint_types[joint], model.joint_id(joint)))


def _run_model(c, a):
    if a.model_cmd == "load":
        _print_model(c.load_model(a.path, name=a.name, position=a.position, orientation=a.orientation,
                                  fixed_base=a.fixed_base, self_collide=a.self_collide,
                                  max_hull_vertices=a.max_hull_vertices))
        return None
    if a.model_cmd == "list":
        for model in c.models().values():
            _print_model(model)
        return None
    return c.remove_model(a.id)


def _run_joint(c, a):
    if a.joint_cmd == "add":
        print(c.add_joint(a.kind, a.body_a, a.body_b or None, anchor=a.anchor, axis=a.axis,
                          length=a.length, limits=a.limits, damping=a.damping, friction=a.friction))
        return None
    if a.joint_cmd == "state":
        js = c.request_joint_state()
        for j, m, name, q, v, u in zip(js.joint_ids, js.model_ids, js.names, js.positions, js.velocities, js.efforts):
            print("joint %d model %d %s position %.9g velocity %.9g effort %.9g" % (j, m, name, q, v, u))
        return None
    if a.joint_cmd == "set":
        fields = {k: getattr(a, k) for k in ("torque", "target_position", "target_velocity", "kp", "kd",
                                             "effort_limit", "velocity_limit")}
        return c.set_joint_actuator(a.id, **fields)
    if a.joint_cmd == "clear":
        return c.clear_joint_actuators([a.id])
    return c.remove_joint(a.id)


def _ray(c, a):
    hit, ids, points, normals, dist = c.ray_cast([a.origin], [a.direction], a.max_distance, ignore=a.ignore)
    if not hit[0]:
        print("miss")
        return
    print("hit body %d distance %.9g point %.9g %.9g %.9g normal %.9g %.9g %.9g"
          % (ids[0], dist[0], *points[0], *normals[0]))


def _compare(c, a):
    from .fleet import Fleet, fork_compare
    fleet = Fleet(workers=a.workers or min(len(a.methods), os.cpu_count() or 1), address=a.address)
    try:
        df = fork_compare(c, a.methods, a.steps, fleet=fleet, plot=a.plot, progress=sys.stderr.isatty())
    finally:
        fleet.close()
    table = df.drop(columns=[k for k in ("trajectory", "traceback") if k in df.columns])
    if a.csv:
        table.to_csv(a.csv, index=False)
    print(table[["tag", "max_penetration", "energy_drift", "ms_per_step", "mean_contacts", "departure",
                 "state_hash", "error"]].to_string(index=False))


def _run(c, a):
    if a.cmd == "status":
        for k, v in c.wait_for_server(timeout=max(a.timeout, 1.5)).as_dict().items():
            print("%-24s %s" % (k, v))
        return
    if a.cmd == "add":
        if a.shape == "plane":
            bid = c.add_plane((a.nx, a.ny, a.nz), a.offset, restitution=a.restitution, friction=a.friction)
        elif a.shape == "heightfield":
            bid = c.add_heightfield(a.path, a.spacing, rows=a.rows, cols=a.cols, scale=a.scale, offset=a.offset,
                                    position=a.position, restitution=a.restitution, friction=a.friction,
                                    name=a.name)
        elif a.shape == "mesh":
            bid = c.add_mesh(a.path, scale=a.scale, position=a.position, restitution=a.restitution,
                             friction=a.friction, name=a.name)
        else:
            kw = dict(position=a.position, velocity=a.velocity, mass=a.mass, density=a.density,
                      restitution=a.restitution, friction=a.friction, fixed=a.fixed, name=a.name)
            bid = (c.add_sphere(a.radius, **kw) if a.shape == "sphere"
                   else c.add_box((a.hx, a.hy, a.hz), **kw))
        print(bid)
        return
    if a.cmd == "compare":
        _compare(c, a)
        return
    if a.cmd == "ray":
        _ray(c, a)
        return
    if a.cmd == "joint":
        r = _run_joint(c, a)
        if r is None:
            return
    elif a.cmd == "sensor":
        r = c.add_contact_sensor(a.body, a.name) if a.sensor_cmd == "contact" else c.remove_sensor(a.name)
    elif a.cmd == "model":
        r = _run_model(c, a)
        if r is None:
            return
    elif a.cmd == "remove":
        r = c.remove_body(a.id)
    elif a.cmd == "method":
        params = dict(kv.split("=", 1) if "=" in kv else (kv, "") for kv in a.params)
        r = c.set_contact_method(a.name, **params)
    elif a.cmd == "step":
        # waits as long as the server reports progress, a.timeout s of silence at most
        bar = sys.stderr.isatty() if a.progress is None else a.progress
        r = c.step(a.n, timeout=a.timeout, progress=bar)
    else:
        r = getattr(c, a.cmd)()
    print("ok: step %d, time %.6f s%s" % (r.step, r.time, ": " + r.message if r.message else ""))


def main(argv=None):
    a = _parser().parse_args(argv)
    try:
        client = Client(url=a.lcm_url, prefix=a.prefix, timeout=a.timeout, auth_key_file=a.auth_key_file)
    except AuthKeyError as e:
        print("contactsim-py: %s" % e, file=sys.stderr)
        return 2
    with client as c:
        try:
            _run(c, a)
        except TimeoutError as e:
            print("contactsim-py: %s" % e, file=sys.stderr)
            return 2
        except CommandError as e:
            print("contactsim-py: %s" % e, file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
