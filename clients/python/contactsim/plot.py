"""Plots a recorded contactsim run: ``python -m contactsim.plot LOG -o DIR``.

Reads the log with ``contactsim.logread.read_log`` (a progress bar on long
logs) and writes four PNG files into DIR, each over simulated time:

* energy.png       kinetic, potential and total energy (J)
* penetration.png  maximum penetration depth (mm)
* contacts.png     number of contact points
* force.png        total normal contact force (N)

and, when the log holds JOINT_STATE messages, joints.png: each joint's
position, velocity and actuator effort.

Matplotlib runs on its Agg backend, so no display is needed.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only: works without a display, in CI and over ssh
import matplotlib.pyplot as plt  # noqa: E402

from .logread import read_log  # noqa: E402

# Logs above this size take seconds to decode in Python: show a bar.
LONG_LOG_BYTES = 4 << 20


def _figure(title, ylabel):
    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=100)
    ax.set_title(title)
    ax.set_xlabel("simulated time (s)")
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    return fig, ax


def _save(fig, out_dir, name):
    path = os.path.join(out_dir, name)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return path


def plot_log(log, out_dir):
    """Writes the four plots of a ``read_log`` result into out_dir; returns their paths."""
    os.makedirs(out_dir, exist_ok=True)
    paths = []
    fig, ax = _figure("Energy of the dynamic bodies", "energy (J)")
    ax.plot(log.time, log.kinetic_energy, label="kinetic")
    ax.plot(log.time, log.potential_energy, label="potential (zero at z = 0)")
    ax.plot(log.time, log.kinetic_energy + log.potential_energy, label="total", linestyle="--")
    ax.legend()
    paths.append(_save(fig, out_dir, "energy.png"))

    c = log.contacts
    fig, ax = _figure("Maximum penetration", "depth (mm)")
    ax.plot(c.time, c.max_depth * 1e3)
    paths.append(_save(fig, out_dir, "penetration.png"))

    fig, ax = _figure("Contact points", "count")
    ax.step(c.time, c.count, where="post")
    paths.append(_save(fig, out_dir, "contacts.png"))

    fig, ax = _figure("Total normal contact force", "force (N)")
    ax.plot(c.time, c.total_normal_force)
    paths.append(_save(fig, out_dir, "force.png"))
    if len(log.joints.time):
        paths.append(plot_joints(log.joints, out_dir))
    return paths


def plot_joints(joints, out_dir, name="joints.png"):
    """Position, velocity and effort of every joint over time, one panel each."""
    fig, axes = plt.subplots(3, 1, figsize=(8, 9), dpi=100, sharex=True)
    for ax, values, label in zip(axes, (joints.position, joints.velocity, joints.effort),
                                 ("position (rad or m)", "velocity (rad/s or m/s)", "effort (N m or N)")):
        for k, joint_name in enumerate(joints.names):
            ax.plot(joints.time, values[:, k], label=joint_name)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0].set_title("Joints")
    axes[0].legend(fontsize="small", ncol=4)
    axes[-1].set_xlabel("simulated time (s)")
    return _save(fig, out_dir, name)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m contactsim.plot", description=__doc__.split("\n")[0])
    parser.add_argument("log", help="an LCM log recorded with lcm-logger")
    parser.add_argument("-o", "--out", required=True, help="folder for the PNG files (created if missing)")
    parser.add_argument("--prefix", default=None, help="channel prefix (default: from the log's *_STATE channel)")
    args = parser.parse_args(argv)
    try:
        size = os.path.getsize(args.log)
        log = read_log(args.log, prefix=args.prefix, progress=size > LONG_LOG_BYTES)
    except (OSError, IOError, ValueError) as e:
        print("contactsim.plot: cannot read %s: %s" % (args.log, e), file=sys.stderr)
        return 1
    if len(log.time) == 0:
        print("contactsim.plot: no %s_STATE messages in %s" % (log.prefix, args.log), file=sys.stderr)
        return 1
    for path in plot_log(log, args.out):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
