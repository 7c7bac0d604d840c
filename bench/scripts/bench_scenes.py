#!/usr/bin/env python3
"""Runs every engine x method on every standard scene and writes the tables
into BENCHMARKS.md: the run's machine, build, commit and date between the
run:begin / run:end markers at the top of the file, the tables between the
peers:begin / peers:end markers; the rest of the file is left as it is.
`make bench` runs it.

Engines: contactsim-bench with every registered contact method
(--list-methods), and the peer runners that were built (bench/peers:
Bullet sequential impulse, Box3D's soft step when a Box3D source was given
at configure time, ODE QuickStep and Dantzig, MuJoCo Newton and CG). Each
run is a separate process with --repeat 3 --json; a run that fails (NaN,
explosion, time limit, crash, memory limit) becomes a row that says so and
never stops the driver.

Instructions a step beside the times: each row is run twice more under
valgrind's cachegrind (no cache simulation), for 1 step and for 1 + N steps
(--instruction-steps, 480 by default), both --repeat 1, and the difference
over N is the row's instructions a step, so that the setup, the scene's
loading and the machine's load drop out. The machine's load moves the times
from run to run; it does not move these counts, the figure to steer by on a
shared machine (BENCHMARKS.md, "Speed targets"). --no-instructions skips
them; a row whose counting runs exceed --instruction-timeout shows "-".

Scaling rows after the standard scenes (bench_scaling.py; --no-scaling skips
them): Box3D's stress scenes from 1,000 to 10,000 bodies on 1 and 2 threads.

Usage: bench/scripts/bench_scenes.py [--build-dir build] [--scenes a b] [--repeat 3]
       [--max-seconds 60] [--steps N] [--output BENCHMARKS.md] [--no-write]
       [--no-instructions] [--instruction-steps 480] [--instruction-timeout 900]
"""
import argparse
import datetime
import json
import os
import platform
import re
import resource
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_scaling  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = ["box_pyramid", "sphere_pile", "box_rain", "bounce", "terrain_rain", "heightfield_rain"]
# The scenes on a static triangle mesh or heightfield (ODE and MuJoCo refuse those shapes).
TERRAIN = ("terrain_rain", "heightfield_rain")
BEGIN, END = "<!-- peers:begin -->", "<!-- peers:end -->"
RUN_BEGIN, RUN_END = "<!-- run:begin -->", "<!-- run:end -->"
APEX = 0.5 * 0.5 * 0.9  # m, analytic first apex of the bounce scene (e^2 h)
MEMORY_LIMIT = 6 << 30  # bytes of address space per run: a dense LCP of a 1,000-body pile would take the machine

# Peer rows: (engine, binary, method). Bullet first: the ratio column divides by it; Box3D beside it, the
# peer soft's speed target is set against (targets()).
PEERS = [
    ("bullet", "contactsim-bench-bullet", "sequential_impulse"),
    ("box3d", "contactsim-bench-box3d", "soft_step"),
    ("ode", "contactsim-bench-ode", "quickstep"),
    ("ode", "contactsim-bench-ode", "dantzig"),
    ("mujoco", "contactsim-bench-mujoco", "newton"),
    # MuJoCo's own advice for scenes whose Newton Hessian fills in (the 1,000-body pile)
    ("mujoco", "contactsim-bench-mujoco", "cg"),
]
# The runners that step on --threads threads (MuJoCo through its thread pool, Box3D through its task callbacks).
THREADED = ("contactsim-bench", "contactsim-bench-mujoco", "contactsim-bench-box3d")
# The peers listed before contactsim's rows (Bullet, Box3D); the others come after them.
LEADING_PEERS = 2
# Extra contactsim rows beyond each method's defaults, used when the method is registered.
VARIANTS = {"lcp": [["solver=pgs"], ["solver=lemke"]], "soft": [[], ["precision=float"]]}
# soft's speed target (BENCHMARKS.md, "Speed targets"): at or below Box3D's time as a multiple of Bullet's
# on these scenes, both measured in the same run.
SOFT_TARGET_SCENES = ("box_pyramid", "sphere_pile", "box_rain")


def runs(bin_dir):
    """(engine, binary, method, params) for every row, in table order."""
    out = []
    for engine, binary, method in PEERS[:LEADING_PEERS]:
        if os.path.exists(os.path.join(bin_dir, binary)):
            out.append((engine, binary, method, []))
    names = subprocess.run([os.path.join(bin_dir, "contactsim-bench"), "--list-methods"],
                           capture_output=True, text=True, check=True).stdout.split()
    for method in names:
        for params in VARIANTS.get(method, [[]]):
            out.append(("contactsim", "contactsim-bench", method, params))
    for engine, binary, method in PEERS[LEADING_PEERS:]:
        if os.path.exists(os.path.join(bin_dir, binary)):
            out.append((engine, binary, method, []))
    return out


def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def runner_command(bin_dir, binary, scene, method, params, threads):
    cmd = [os.path.join(bin_dir, binary), "--scene", os.path.join(ROOT, "config", "scenes", scene + ".pbtxt"),
           "--method", method, "--json"]
    for p in params:
        cmd += ["--param", p]
    if binary in THREADED:
        cmd += ["--threads", str(threads)]  # Bullet and ODE step on one thread
    return cmd


def counted_instructions(cmd, timeout):
    """The instructions valgrind counts for cmd (its "I refs"), or None."""
    vg = ["valgrind", "--tool=cachegrind", "--cache-sim=no", "--cachegrind-out-file=/dev/null"]
    try:
        proc = subprocess.run(vg + cmd, stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None
    m = re.search(r"I\s+refs:\s+([\d,]+)", proc.stderr)
    return int(m.group(1).replace(",", "")) if m and proc.returncode == 0 else None


def instructions_per_step(bin_dir, binary, scene, method, params, args):
    """(I(1 + N steps) - I(1 step)) / N on one thread, or None when a run failed or took too long."""
    n = args.instruction_steps
    cmd = runner_command(bin_dir, binary, scene, method, params, 1) + ["--repeat", "1", "--max-seconds", "0"]
    one = counted_instructions(cmd + ["--steps", "1"], args.instruction_timeout)
    if one is None:
        return None
    more = counted_instructions(cmd + ["--steps", str(1 + n)], args.instruction_timeout)
    return None if more is None else (more - one) / n


def run_one(bin_dir, binary, scene, method, params, args):
    cmd = runner_command(bin_dir, binary, scene, method, params, args.threads)
    cmd += ["--repeat", str(args.repeat), "--max-seconds", str(args.max_seconds)]
    if args.steps:
        cmd += ["--steps", str(args.steps)]
    # each repeat may step max_seconds; allow for building, measuring and a last slow step
    return run_command(cmd, args.max_seconds * args.repeat + 600)


def run_command(cmd, timeout):
    """The run's JSON object, or {"status": why it gave none}."""
    try:
        proc = subprocess.run(cmd, stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=timeout,
                              preexec_fn=limit_memory)
    except subprocess.TimeoutExpired:
        return {"status": "killed: no result after %d s" % timeout}
    lines = [l for l in proc.stdout.splitlines() if l.startswith("{")]
    if lines:
        try:
            return json.loads(lines[-1])
        except json.JSONDecodeError:
            pass
    why = "signal %d" % -proc.returncode if proc.returncode < 0 else "exit %d" % proc.returncode
    tail = (proc.stderr.strip().splitlines() or [""])[-1][:120]
    return {"status": "crashed (%s)%s" % (why, ": " + tail if tail else "")}


def fmt(v, digits=3):
    if v is None:
        return "-"
    if v == 0:
        return "0"
    return "%.*g" % (digits, v)


def failed(r):
    return r.get("status", "ok") != "ok"


def short_status(r):
    s = r.get("status", "?")
    if s == "ok":
        return "ok"
    return "**%s**" % s.replace("|", "/")


def min_distance(r):
    """The smallest gap between two bodies over the run (negative: overlap)."""
    if "min_distance" not in r:
        return "-"  # a row from before the bench measured it
    d = r["min_distance"]
    return "> 10 mm" if d is None else "%s mm" % fmt(1e3 * d)


def table(scene, rows):
    # a Bullet run that hit the time limit still has a per-step time to divide by
    bullet = next((r for r in rows if r["engine"] == "bullet" and r.get("steps_done", 0) > 0), None)
    extra = {"box_pyramid": "top displacement", "bounce": "rebound height (analytic 0.225 m)",
             "terrain_rain": "fell through", "heightfield_rain": "fell through"}.get(scene)
    head = ["engine", "method", "ms/step (min-max)", "vs Bullet", "instructions/step (vs Bullet)", "max penetration",
            "min distance", "final KE"]
    if extra:
        head.append(extra)
    head += ["peak memory", "status"]
    out = ["| " + " | ".join(head) + " |", "|" + "|".join(["---", "---"] + ["---:"] * (len(head) - 3) + ["---"]) + "|"]
    for r in rows:
        ms = r.get("ms_per_step")
        has_time = ms is not None and r.get("steps_done", 0) > 0
        cells = [r["engine"], r["label"],
                 "%s (%s-%s)" % (fmt(ms), fmt(r.get("ms_per_step_min")), fmt(r.get("ms_per_step_max"))) if has_time else "-",
                 "%.2fx" % (ms / bullet["ms_per_step"]) if has_time and bullet else "-",
                 instruction_cell(r, bullet),
                 "%s mm" % fmt(1e3 * r["max_penetration"]) if r.get("max_penetration") is not None else "-",
                 min_distance(r),
                 "%s J" % fmt(r["final_kinetic_energy"]) if r.get("final_kinetic_energy") is not None else "-"]
        if scene == "box_pyramid":
            cells.append("%s m" % fmt(r["top_displacement"]) if r.get("top_displacement") is not None else "-")
        elif scene in TERRAIN:
            cells.append(fmt(r.get("fell_through")) if r.get("fell_through") is not None else "-")
        elif scene == "bounce":
            h = r.get("rebound_height")
            cells.append("%.4f m (%+.1f%%)" % (h, 100 * (h - APEX) / APEX) if h is not None else "no rebound")
        cells.append("%s MiB" % fmt(r["peak_rss_mb"]) if r.get("peak_rss_mb") is not None else "-")
        cells.append(short_status(r))
        out.append("| " + " | ".join(cells) + " |")
    return out


def instruction_cell(r, bullet):
    n = r.get("instructions_per_step")
    if n is None:
        return "-"
    base = (bullet or {}).get("instructions_per_step")
    count = "%.3gM" % (n / 1e6) if n >= 1e6 else "%.3gk" % (n / 1e3)
    return count + (" (%.2fx)" % (n / base) if base else "")


def machine():
    cpu = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return "%d x %s, %s %s" % (os.cpu_count() or 0, cpu, platform.system(), platform.release())


def build_type(build_dir):
    try:
        with open(os.path.join(build_dir, "CMakeCache.txt")) as f:
            for line in f:
                if line.startswith("CMAKE_BUILD_TYPE:"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return "?"


def git_commit():
    try:
        return subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "?"


def targets(results):
    """The standard scenes' first targets (BENCHMARKS.md), checked against this run's rows."""
    def row(scene, engine, label):
        return next((r for r in results if r["scene_name"] == scene and r["engine"] == engine
                     and r["label"] == label), None)
    out = ["The standard scenes' first targets, from this run:", ""]
    lcp = [r["label"] for r in results if r["engine"] == "contactsim" and r["label"].startswith("lcp")]
    pgs = next((l for l in lcp if "pgs" in l), lcp[0] if lcp else None)
    ran = {r["scene_name"] for r in results}  # a run of some scenes (--scenes) checks only theirs
    for scene in [s for s in ("box_pyramid", "sphere_pile") if s in ran]:
        bullet = row(scene, "bullet", "sequential_impulse")
        r = row(scene, "contactsim", pgs) if pgs else None
        if not pgs:
            out.append("* %s: no `lcp` method is registered in this build; nothing to compare." % scene)
        elif not r or not bullet or failed(r) or failed(bullet):
            out.append("* %s, %s: **not met**, the run did not complete (%s)." % (
                scene, pgs, (r or {}).get("status", "no row")))
        else:
            ratio = r["ms_per_step"] / bullet["ms_per_step"]
            pen = r["max_penetration"] <= bullet["max_penetration"]
            line = "* %s, %s: %.2fx Bullet's ms/step (%s), max penetration %s mm vs Bullet's %s mm (%s)" % (
                scene, pgs, ratio, "met" if ratio <= 1 else "**missed by %.0f%%**" % (100 * (ratio - 1)),
                fmt(1e3 * r["max_penetration"]), fmt(1e3 * bullet["max_penetration"]), "met" if pen else "**missed**")
            if scene == "box_pyramid":
                d = r.get("top_displacement")
                line += ", top moved %s m (%s)" % (fmt(d), "met" if d is not None and d < 0.05 else "**missed**")
            out.append(line + ".")
    for label in ["impulse"] + ([pgs] if pgs else []) if "bounce" in ran else []:
        r = row("bounce", "contactsim", label)
        h = r.get("rebound_height") if r else None
        if h is None:
            out.append("* bounce, %s: **no rebound measured** (%s)." % (label, (r or {}).get("status", "no row")))
        else:
            err = (h - APEX) / APEX
            out.append("* bounce, %s: apex %.4f m, %+.1f%% of 0.225 m (%s)." % (
                label, h, 100 * err, "met" if abs(err) <= 0.02 else "**missed**"))
    out += soft_targets(results, row)
    out += terrain_targets(results)
    bad = ["%s on %s (%s)" % (r["label"], r["scene_name"], r.get("status")) for r in results
           if r["engine"] == "contactsim" and failed(r)]
    out.append("* Every contact method completes every scene: %s." % (
        "met" if not bad else "**not met**: " + "; ".join(bad)))
    return out + [""]


def soft_targets(results, row):
    """soft's speed target: its ms/step as a multiple of Bullet's at or below Box3D's, both from this run,
    with the instruction ratios beside; unchecked in a build without the Box3D runner."""
    out = []
    ran = {r["scene_name"] for r in results}
    for scene in [s for s in SOFT_TARGET_SCENES if s in ran]:
        bullet = row(scene, "bullet", "sequential_impulse")
        box3d = row(scene, "box3d", "soft_step")
        for label in ("soft", "soft precision=float"):
            r = row(scene, "contactsim", label)
            if not r:
                continue
            if not bullet or failed(r) or failed(bullet):
                out.append("* %s, %s: **not met**, the run did not complete (%s)." % (
                    scene, label, (r if failed(r) else bullet or {}).get("status", "no row")))
                continue
            ratio = r["ms_per_step"] / bullet["ms_per_step"]
            if box3d is None or failed(box3d):
                out.append("* %s, %s: %.2fx Bullet's ms/step; **not checked**, no completed Box3D row (%s; "
                           "configure with CONTACTSIM_BOX3D_SOURCE_DIR)." % (
                               scene, label, ratio, (box3d or {}).get("status", "no runner")))
                continue
            target = box3d["ms_per_step"] / bullet["ms_per_step"]
            line = "* %s, %s: %.2fx Bullet's ms/step against Box3D's %.2fx (%s)" % (
                scene, label, ratio, target,
                "met" if ratio <= target else "**missed by %.0f%%**" % (100 * (ratio / target - 1)))
            counts = [x.get("instructions_per_step") for x in (r, bullet, box3d)]
            if all(counts):
                line += "; in instructions %.2fx against %.2fx" % (counts[0] / counts[1], counts[2] / counts[1])
            out.append(line + ".")
    return out


def terrain_targets(results):
    """The terrain scenes' targets: contactsim's fastest method at or below Bullet's ms/step, its peak
    memory within 1.5x Bullet's, and no body through the surface under any engine."""
    out = []
    for scene in TERRAIN:
        rows = [r for r in results if r["scene_name"] == scene and not failed(r)]
        bullet = next((r for r in rows if r["engine"] == "bullet"), None)
        ours = [r for r in rows if r["engine"] == "contactsim"]
        if not rows:
            continue
        if not bullet or not ours:
            out.append("* %s: **not met**, no completed %s row." % (scene, "Bullet" if not bullet else "contactsim"))
            continue
        best = min(ours, key=lambda r: r["ms_per_step"])
        ratio = best["ms_per_step"] / bullet["ms_per_step"]
        memory = best["peak_rss_mb"] / bullet["peak_rss_mb"]
        through = ["%s %s (%d)" % (r["engine"], r["label"], r["fell_through"]) for r in rows if r.get("fell_through")]
        out.append("* %s, fastest method %s: %.2fx Bullet's ms/step (%s), peak memory %.2fx Bullet's (%s); "
                   "bodies through the surface: %s." % (
                       scene, best["label"], ratio, "met" if ratio <= 1 else "**missed by %.0f%%**" % (100 * (ratio - 1)),
                       memory, "met" if memory <= 1.5 else "**missed**",
                       "none (met)" if not through else "**" + ", ".join(through) + "**"))
    return out


def run_line(args, started, load_before):
    """The one line that says where and when the generated tables were measured."""
    return "\n".join([
        RUN_BEGIN,
        "Generated tables: %s; build %s, commit %s; %s; load average %s before the run." % (
            machine(), build_type(args.build_dir), git_commit(), started.strftime("%Y-%m-%d %H:%M UTC"),
            load_before),
        RUN_END])


def render(results, args):
    out = [BEGIN,
           "<!-- Generated by bench/scripts/bench_scenes.py (make bench); edits here are overwritten. -->",
           "",
           "Reproduce: `make bench` (or `.venv/bin/python bench/scripts/bench_scenes.py --build-dir build "
           "--repeat %d --max-seconds %g`). Each row is one process: `contactsim-bench` or a peer runner "
           "`contactsim-bench-{bullet,box3d,ode,mujoco}` with `--scene config/scenes/NAME.pbtxt --method M "
           "--repeat %d --json` (and `--threads %d` for contactsim, Box3D and MuJoCo; Bullet and ODE step on one); "
           "ms/step is the median of the repeats (stepping loop only), min-max "
           "in brackets; a repeat stops after %g s of stepping (status `timeout`). "
           "Instructions a step: valgrind's cachegrind count of a run of 1 + N steps less one of 1 step, over N "
           "(N = %d, one thread, `--repeat 1`; bench/scripts/bench_scenes.py), which includes the bench's own "
           "collision pass that measures penetration; the machine's load does not move it. "
           "Machine, build and commit: the line at the top of this file." % (
               args.repeat, args.max_seconds, args.repeat, args.threads, args.max_seconds,
               args.instruction_steps),
           ""]
    for scene in args.scenes:
        rows = [r for r in results if r["scene_name"] == scene]
        if not rows:
            continue
        first = next((r for r in rows if r.get("bodies")), {})
        out += ["### %s (%s bodies, %s steps of %s s)" % (
            scene, first.get("bodies", "?"), first.get("steps", "?"), fmt(first.get("dt"), 6)), ""]
        out += table(scene, rows)
        out.append("")
    out += targets(results)
    out.append(END)
    return "\n".join(out)


def replace_region(text, begin, end, region):
    """text with the region between begin and end replaced, or None when a marker is missing."""
    if begin not in text or end not in text:
        return None
    pre, rest = text.split(begin, 1)
    return pre + region + rest.split(end, 1)[1]


def write(path, run, region, scaling_region=None):
    text = open(path).read() if os.path.exists(path) else "# Benchmarks\n"
    replaced = replace_region(text, BEGIN, END, region)
    if replaced is None:
        replaced = text.rstrip("\n") + "\n\n## Standard scenes against Bullet, ODE and MuJoCo\n\n" + region + "\n"
    if scaling_region:
        with_scaling = replace_region(replaced, bench_scaling.BEGIN, bench_scaling.END, scaling_region)
        replaced = with_scaling if with_scaling is not None else (
            replaced.rstrip("\n") + "\n\n## Scaling: 1,000 to 10,000 bodies\n\n" + scaling_region + "\n")
    text = replace_region(replaced, RUN_BEGIN, RUN_END, run)
    if text is None:  # the run line goes right under the title
        title, _, rest = replaced.partition("\n")
        text = title + "\n\n" + run + "\n" + rest
    with open(path, "w") as f:
        f.write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"))
    ap.add_argument("--scenes", nargs="+", default=SCENES, choices=SCENES)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--max-seconds", type=float, default=60.0, help="stepping time per repeat before giving up")
    ap.add_argument("--threads", type=int, default=1,
                    help="contactsim's, Box3D's and MuJoCo's threads (Bullet and ODE use one)")
    ap.add_argument("--steps", type=int, default=0, help="override the scenes' steps (for a quick look)")
    ap.add_argument("--no-instructions", dest="instructions", action="store_false",
                    help="skip the instruction counts (valgrind) beside the times")
    ap.add_argument("--instruction-steps", type=int, default=480, help="N of the counting runs (1 + N steps less 1)")
    ap.add_argument("--instruction-timeout", type=float, default=900.0, help="seconds a counting run may take")
    ap.add_argument("--output", default=os.path.join(ROOT, "BENCHMARKS.md"))
    ap.add_argument("--json-out", default=None, help="also write every run's JSON here (default BUILD/bench_scenes.json)")
    ap.add_argument("--no-write", action="store_true", help="print the tables instead of writing BENCHMARKS.md")
    ap.add_argument("--only", nargs="+", default=None, metavar="ENGINE[:METHOD]",
                    help="run only these rows, e.g. bullet contactsim:penalty")
    ap.add_argument("--update-json", default=None, metavar="FILE",
                    help="replace (or add) this run's rows in a saved run's JSON and render that")
    ap.add_argument("--from-json", default=None, help="render the tables from a previous run's JSON, running nothing")
    ap.add_argument("--no-scaling", dest="scaling", action="store_false",
                    help="skip the scaling rows (1,000 to 10,000 bodies; bench_scaling.py)")
    ap.add_argument("--scaling-only", action="store_true",
                    help="run and write only the scaling rows, leaving the standard tables as they are")
    args = ap.parse_args()
    args.build_dir = os.path.abspath(args.build_dir)
    if args.instructions and shutil.which("valgrind") is None:
        print("valgrind not found (make deps installs it): no instruction counts", file=sys.stderr)
        args.instructions = False
    bin_dir = os.path.join(args.build_dir, "bin")

    started = datetime.datetime.now(datetime.timezone.utc)
    load_before = "%.2f" % os.getloadavg()[0]
    if args.from_json:
        with open(args.from_json) as f:
            saved = json.load(f)
        results, meta = saved["runs"], saved["meta"]
        started = datetime.datetime.fromisoformat(meta["started"])
        load_before, args.repeat, args.max_seconds = meta["load_before"], meta["repeat"], meta["max_seconds"]
        args.threads = meta.get("threads", 1)  # runs saved before threads were recorded used one
        args.instruction_steps = meta.get("instruction_steps", args.instruction_steps)
        return finish(results, args, started, load_before, saved.get("scaling", []))
    if args.scaling_only:
        return write_scaling_only(args, run_scaling(bin_dir, args))
    plan = [(scene,) + r for scene in args.scenes for r in runs(bin_dir)
            if not args.only or r[0] in args.only or "%s:%s" % (r[0], r[2]) in args.only]
    results = []
    t_all = time.time()
    for i, (scene, engine, binary, method, params) in enumerate(plan, 1):
        label = method + ("" if not params else " " + " ".join(params))
        print("[%2d/%d] %-12s %-10s %-28s" % (i, len(plan), scene, engine, label), end="", flush=True)
        t0 = time.time()
        r = run_one(bin_dir, binary, scene, method, params, args)
        # not the terrain scenes: their first 480 steps are 30-90 ms each natively, tens of minutes
        # a count under valgrind, past --instruction-timeout for every row
        if args.instructions and not failed(r) and scene not in TERRAIN:
            r["instructions_per_step"] = instructions_per_step(bin_dir, binary, scene, method, params, args)
        r.update(engine=engine, label=label, scene_name=scene)
        results.append(r)
        ms = r.get("ms_per_step")
        print(" %9s ms/step  %5.0f s  %s" % (fmt(ms), time.time() - t0, r.get("status")), flush=True)
    print("all runs: %.0f s" % (time.time() - t_all))
    scaling = run_scaling(bin_dir, args) if args.scaling else []
    json_out = args.json_out or os.path.join(args.build_dir, "bench_scenes.json")
    with open(json_out, "w") as f:
        json.dump({"meta": {"started": started.isoformat(), "load_before": load_before, "repeat": args.repeat,
                            "max_seconds": args.max_seconds, "threads": args.threads,
                            "instruction_steps": args.instruction_steps}, "runs": results, "scaling": scaling},
                  f, indent=1)
    print("results: %s" % json_out)
    if args.update_json:
        with open(args.update_json) as f:
            saved = json.load(f)
        key = lambda r: (r["scene_name"], r["engine"], r["label"])
        fresh = {key(r): r for r in results}
        merged = [fresh.pop(key(r), r) for r in saved["runs"]] + list(fresh.values())
        with open(args.update_json, "w") as f:
            json.dump({"meta": saved["meta"], "runs": merged}, f, indent=1)
        meta = saved["meta"]
        started = datetime.datetime.fromisoformat(meta["started"])
        return finish(merged, args, started, meta["load_before"], scaling or saved.get("scaling", []))
    return finish(results, args, started, load_before, scaling)


def run_scaling(bin_dir, args):
    """The scaling rows (bench_scaling.py), each one process, in table order."""
    names = subprocess.run([os.path.join(bin_dir, "contactsim-bench"), "--list-methods"],
                           capture_output=True, text=True, check=True).stdout.split()
    rows = bench_scaling.plan(bin_dir, names)
    out = []
    t_all = time.time()
    for i, (scene, engine, binary, method, threads) in enumerate(rows, 1):
        print("[%2d/%d] %-18s %-10s %-18s %d thread(s)" % (i, len(rows), scene, engine, method, threads), end="",
              flush=True)
        t0 = time.time()
        cmd = bench_scaling.command(ROOT, bin_dir, scene, binary, method, threads, args.max_seconds)
        r = run_command(cmd, args.max_seconds + 600)
        r.update(engine=engine, label=method, scene_name=scene, threads_asked=threads)
        out.append(r)
        print(" %9s ms/step  %5.0f s  %s" % (fmt(r.get("ms_per_step")), time.time() - t0, r.get("status")), flush=True)
    print("scaling rows: %.0f s" % (time.time() - t_all))
    return out


def write_scaling_only(args, scaling):
    json_out = args.json_out or os.path.join(args.build_dir, "bench_scaling.json")
    with open(json_out, "w") as f:
        json.dump({"scaling": scaling, "load_before": "%.2f" % os.getloadavg()[0]}, f, indent=1)
    region = bench_scaling.render(scaling, fmt, short_status)
    text = open(args.output).read() if os.path.exists(args.output) else "# Benchmarks\n"
    replaced = replace_region(text, bench_scaling.BEGIN, bench_scaling.END, region)
    if replaced is None:
        replaced = text.rstrip("\n") + "\n\n## Scaling: 1,000 to 10,000 bodies\n\n" + region + "\n"
    if args.no_write:
        print(region)
    else:
        with open(args.output, "w") as f:
            f.write(replaced)
        print("wrote %s (scaling rows; results %s)" % (args.output, json_out))
    return 0


def finish(results, args, started, load_before, scaling=()):
    run = run_line(args, started, load_before)
    region = render(results, args)
    scaling_region = bench_scaling.render(list(scaling), fmt, short_status) if scaling else None
    if args.no_write:
        print(run + "\n\n" + region + ("\n\n" + scaling_region if scaling_region else ""))
    else:
        write(args.output, run, region, scaling_region)
        print("wrote %s" % args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
