"""Fleet throughput (BENCHMARKS.md, "Fleet"): jobs per minute on 1 and 2
local Ray workers and sequentially without Ray, Ray's and the workers'
start-up, and the per-job start-up cost (a 1-step job).

    CONTACTSIM_BUILD_DIR=build .venv/bin/python bench/scripts/bench_fleet.py [--jobs 16] [--steps 480] [--workers 1,2]

Every job is the default scene (7 bodies) under the impulse method with
its own iteration count, `--steps` steps, collecting the hash and metrics.
Prints a Markdown table.
"""
import argparse
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "clients" / "python"))

from contactsim.fleet import Fleet, Job, run_sequential  # noqa: E402


def jobs(n, steps):
    return [Job(scene=REPO / "config" / "scenes" / "default.pbtxt", method="impulse",
                params={"iterations": 10 + i}, steps=steps, tag=i) for i in range(n)]


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


TINY = 8   # 1-step jobs per worker: what a job costs besides its steps


def on_fleet(workers, n, steps):
    """(Ray start s, workers and servers ready s, sweep s, s of a worker per
    1-step job, per-step ms) for one fleet size."""
    fleet, t_init = timed(lambda: Fleet(workers=workers, progress=False))
    try:
        _, t_servers = timed(fleet.where)
        df, t_sweep = timed(lambda: fleet.map(jobs(n, steps)))
        assert (df["error"] == "").all(), df["error"].tolist()
        _, t_tiny = timed(lambda: fleet.map(jobs(workers * TINY, 1)))
    finally:
        fleet.close()
    return t_init, t_servers, t_sweep, t_tiny / TINY, df["ms_per_step"].median()


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--jobs", type=int, default=16)
    p.add_argument("--steps", type=int, default=480)
    p.add_argument("--workers", default="1,2")
    a = p.parse_args()
    print("| run | Ray start s | servers ready s | %d jobs s | jobs/min | ms per 1-step job | ms/step (median) |"
          % a.jobs)
    print("|---|---:|---:|---:|---:|---:|---:|")
    # sequential: one server started per run_sequential call, counted in its time
    df, t = timed(lambda: run_sequential(jobs(a.jobs, a.steps)))
    _, t_tiny = timed(lambda: run_sequential(jobs(TINY, 1)))
    print("| sequential, no Ray | - | - | %.1f | %.0f | %.0f | %.3f |" % (
        t, 60 * a.jobs / t, 1000 * t_tiny / TINY, df["ms_per_step"].median()), flush=True)
    for w in (int(x) for x in a.workers.split(",")):
        init, ready, sweep, tiny, ms = on_fleet(w, a.jobs, a.steps)
        print("| Ray, %d worker%s | %.1f | %.1f | %.1f | %.0f | %.0f | %.3f |" % (
            w, "s" if w > 1 else "", init, ready, sweep, 60 * a.jobs / sweep, 1000 * tiny, ms), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
