"""Fork and compare: snapshot a running world, run it forward under each
method on the fleet, and set the results side by side (docs/fleet.md)."""
import os
import tempfile
from pathlib import Path

import numpy as np

from ..viewer.catalog import catalog_from_snapshot
from .job import Job

COLUMNS = ("method", "params", "max_penetration", "energy_drift", "ms_per_step", "mean_contacts", "departure",
           "state_hash", "error")


def method_spec(item):
    """"name", ("name", {params}), {"method": name, "params": {...}} or
    "name:k=v,k=v" -> (name, params)."""
    if isinstance(item, dict):
        return item["method"], dict(item.get("params") or {})
    if isinstance(item, (tuple, list)):
        return item[0], dict(item[1] if len(item) > 1 else {})
    name, _, rest = str(item).partition(":")
    params = dict(kv.split("=", 1) for kv in rest.split(",") if kv)
    return name, params


def snapshot_bytes(client):
    """The client's world as snapshot bytes. The server writes the file on its
    host: this works when that is this host (or a folder both see)."""
    folder = tempfile.mkdtemp(prefix="contactsim-fork-")
    path = Path(folder) / "fork.pb"
    try:
        client.snapshot(path=path)
        return path.read_bytes()
    finally:
        if path.exists():
            path.unlink()
        os.rmdir(folder)


def departure(traj, ref):
    """Largest distance (m) between the same body in two runs, over the
    bodies and the steps both have."""
    worst = 0.0
    for body, x in (traj or {}).items():
        r = (ref or {}).get(body)
        if r is None:
            continue
        n = min(len(x), len(r))
        if n:
            worst = max(worst, float(np.nanmax(np.linalg.norm(x[:n] - r[:n], axis=1))))
    return worst


def fork_compare(client, methods, steps, *, fleet=None, workers=None, bodies=None, plot=None, progress=False):
    """A DataFrame with one row per method, all from the same snapshot of
    the client's world; ``departure`` is how far each run's bodies get
    from the first method's (m). ``bodies``: ids or names to follow (None:
    every dynamic body). ``plot``: a file to draw departure over the steps
    into. Without ``fleet`` a local one of ``workers`` is made and closed."""
    snap = snapshot_bytes(client)
    if bodies is None:
        bodies = [b["id"] for b in catalog_from_snapshot(snap)["bodies"] if b["motion"] == "dynamic"]
    specs = [method_spec(m) for m in methods]
    jobs = [Job(snapshot=snap, method=name, params=params, steps=steps, bodies=tuple(bodies),
                collect=("hash", "metrics", "trajectory") if bodies else ("hash", "metrics"),
                tag=("%s %s" % (name, " ".join("%s=%s" % kv for kv in sorted(params.items())))).strip())
            for name, params in specs]
    own = fleet is None
    if own:
        from .pool import Fleet
        fleet = Fleet(workers=workers or min(len(jobs), os.cpu_count() or 1))
    try:
        df = fleet.map(jobs, progress=progress)
    finally:
        if own:
            fleet.close()
    trajs = list(df["trajectory"]) if "trajectory" in df.columns else [None] * len(df)
    df["departure"] = [departure(t, trajs[0]) for t in trajs]
    if plot:
        plot_departure(df, trajs, plot)
    return df[[c for c in COLUMNS if c in df.columns] + [c for c in df.columns if c not in COLUMNS]]


def plot_departure(df, trajs, path):
    """departure from the first method over the steps, one line per method."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    for label, t in zip(df["tag"], trajs):
        if not t:
            continue
        n = min(min(len(x) for x in t.values()), min(len(x) for x in trajs[0].values()))
        d = np.max([np.linalg.norm(t[b][:n] - trajs[0][b][:n], axis=1) for b in t], axis=0)
        ax.plot(np.arange(n), d, label=label)
    ax.set_xlabel("step after the fork")
    ax.set_ylabel("departure from %s (m)" % df["tag"].iloc[0])
    ax.legend()
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return path
