#!/usr/bin/env python3
"""Flood: does one client's flood of commands starve another client?

    .venv/bin/python scripts/flood.py [--adds 100000] [--period 0.02] [--running] [--json]

Starts contactsim-server (free_run, paused unless --running, an empty world
on a ground plane). Client A, a process of its own, publishes --adds ADD
commands (small spheres on a grid) as fast as it can without waiting for
replies, and counts the replies it gets by code (RESOURCE_EXHAUSTED when a
limit refuses one) and the ones that never come. Meanwhile client B, a
normal contactsim.Client in this process, sends a cheap command (PAUSE, or
RESUME with --running: neither changes anything) every --period s and
measures each reply's latency. The server's RSS is sampled every 50 ms.

Prints client A's publish rate and replies, client B's latency (median,
p99, max) and unanswered commands, and the server's RSS before, at its
peak, after the flood and after a RESET; --json prints one JSON object.
Exit status 0 when every one of B's commands was answered within its
client's timeout and the server is alive and exits cleanly, else 1. No
latency is asserted: the numbers are measured and written down.
"""
import argparse
import collections
import json
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import lcm  # noqa: E402

import contactsim  # noqa: E402
from server_process import ServerProcess  # noqa: E402

SCENE = 'gravity { z: -9.81 }\nbodies { name: "ground" plane { normal { z: 1 } offset: 0 } }\n'
ADDER_ID = "flood-a"


def adder(url, prefix, count, quiet):
    """Client A: publishes `count` ADDs at once, then waits for the replies
    until `quiet` s pass without one; prints a JSON line."""
    lc = lcm.LCM(url)
    codes = collections.Counter()
    got = set()
    last = [time.monotonic()]  # when the last reply to A came

    def on_reply(channel, data):
        r = contactsim.reply_t.decode(data)
        if r.client_id == ADDER_ID:
            codes[r.code] += 1
            got.add(r.request_id)
            last[0] = time.monotonic()

    sub = lc.subscribe(contactsim.protocol.channel(prefix, "REPLY"), on_reply)
    sub.set_queue_capacity(1000000)
    stop = threading.Event()

    def receive():
        while not stop.is_set():
            lc.handle_timeout(50)

    rx = threading.Thread(target=receive, daemon=True)
    rx.start()
    side = int(count ** (1 / 3)) + 1
    m = contactsim.body_cmd_t()
    m.client_id, m.op, m.shape, m.radius, m.mass = ADDER_ID, m.ADD, m.SPHERE, 0.04, 0.1
    m.orientation = [1.0, 0.0, 0.0, 0.0]
    payloads = []
    for i in range(count):
        m.request_id = i + 1
        m.position = [0.1 * (i % side), 0.1 * ((i // side) % side), 0.05 + 0.1 * (i // (side * side))]
        payloads.append(m.encode())
    channel = contactsim.protocol.channel(prefix, "BODY_CMD")
    t0 = time.monotonic()
    for p in payloads:
        lc.publish(channel, p)
    publish_s = time.monotonic() - t0
    last[0] = time.monotonic()
    while len(got) < count and time.monotonic() - last[0] < quiet:
        time.sleep(0.05)
    done_s = time.monotonic() - t0
    stop.set()
    rx.join(2.0)
    print(json.dumps(dict(published=count, publish_s=round(publish_s, 3), replies=len(got),
                          unanswered=count - len(got), replies_s=round(done_s, 3),
                          codes={contactsim.errors.CODE_NAMES.get(k, str(k)): v for k, v in sorted(codes.items())})),
          flush=True)


def percentile(values, q):
    if not values:
        return None
    s = sorted(values)
    return s[min(len(s) - 1, int(round(q * (len(s) - 1))))]


def flood(args):
    srv = ServerProcess(args.build_dir, scene_text=SCENE, tag="FLOOD", timeout=args.timeout)
    srv.start()
    client = srv.client
    client.step(1)
    if args.running:
        client.resume()
    cheap = client.resume if args.running else client.pause
    rss = []
    stop_rss = threading.Event()

    def sample():
        while not stop_rss.is_set():
            rss.append((time.monotonic(), srv.rss_kib()))
            time.sleep(0.05)

    time.sleep(0.5)
    rss_before = srv.rss_kib()
    sampler = threading.Thread(target=sample, daemon=True)
    sampler.start()

    latencies, unanswered, errors = [], 0, collections.Counter()
    stop_b = threading.Event()

    def client_b():
        nonlocal unanswered
        next_t = time.monotonic()
        while not stop_b.is_set():
            t = time.monotonic()
            try:
                cheap()
                latencies.append(time.monotonic() - t)
            except contactsim.TimeoutError:
                unanswered += 1
            except contactsim.CommandError as e:
                latencies.append(time.monotonic() - t)
                errors[e.code_name] += 1
            next_t += args.period
            time.sleep(max(0.0, next_t - time.monotonic()))

    b = threading.Thread(target=client_b, daemon=True)
    b.start()
    time.sleep(1.0)  # B's latency before the flood
    n_quiet = len(latencies)
    quiet_latencies = list(latencies)
    t0 = time.monotonic()
    proc = subprocess.run([sys.executable, __file__, "--role", "adder", "--url", srv.url, "--prefix", srv.prefix,
                           "--adds", str(args.adds), "--quiet", str(args.quiet)],
                          capture_output=True, text=True, timeout=args.max_seconds)
    flood_s = time.monotonic() - t0
    try:
        a = json.loads(proc.stdout.strip().splitlines()[-1])
    except (IndexError, ValueError):
        a = dict(error=proc.stdout[-2000:] + proc.stderr[-2000:])
    time.sleep(1.0)  # and after it
    stop_b.set()
    b.join(args.timeout + 5)
    alive = srv.alive()
    rss_after = srv.rss_kib()
    num_bodies = None
    rss_after_reset = None
    if alive:
        try:
            st = client.wait_for_status(lambda s: True, timeout=5.0)
            num_bodies = st.num_bodies
            client.reset()
            time.sleep(1.0)
            rss_after_reset = srv.rss_kib()
        except contactsim.CommandError:
            pass
    stop_rss.set()
    sampler.join(1.0)
    rc = srv.stop()
    srv.cleanup()
    during = latencies[n_quiet:]
    ms = lambda v: None if v is None else round(1000 * v, 2)  # noqa: E731
    result = dict(
        adds=args.adds, running=args.running, period_s=args.period, client_timeout_s=args.timeout,
        client_a=a, flood_s=round(flood_s, 2), bodies_after=num_bodies,
        client_b=dict(sent=len(latencies) + unanswered, answered=len(latencies), unanswered=unanswered,
                      errors=dict(errors),
                      quiet_median_ms=ms(statistics.median(quiet_latencies)) if quiet_latencies else None,
                      median_ms=ms(statistics.median(during)) if during else None,
                      p99_ms=ms(percentile(during, 0.99)), max_ms=ms(max(during)) if during else None),
        rss_kib=dict(before=rss_before, peak=max((k for _, k in rss if k is not None), default=None),
                     after=rss_after, after_reset=rss_after_reset),
        server_alive=alive, server_exit=rc)
    result["ok"] = alive and rc == 0 and unanswered == 0 and len(latencies) > 0
    return result


def print_result(r):
    a, b, m = r["client_a"], r["client_b"], r["rss_kib"]
    print("flood: %d ADDs (server %s)" % (r["adds"], "running" if r["running"] else "paused"))
    if "error" in a:
        print("  client A failed: %s" % a["error"])
    else:
        print("  client A: published in %.2f s (%.0f/s); %d replies in %.2f s %s; %d unanswered" % (
            a["publish_s"], a["published"] / max(a["publish_s"], 1e-9), a["replies"], a["replies_s"], a["codes"],
            a["unanswered"]))
    print("  client B: %d commands every %g s, %d answered, %d unanswered (timeout %g s)%s" % (
        b["sent"], r["period_s"], b["answered"], b["unanswered"], r["client_timeout_s"],
        ", errors %s" % b["errors"] if b["errors"] else ""))
    print("  client B latency: before the flood median %s ms; during and after: median %s ms, p99 %s ms, max %s ms" % (
        b["quiet_median_ms"], b["median_ms"], b["p99_ms"], b["max_ms"]))
    print("  server RSS KiB: before %s, peak %s, after %s, after RESET %s; bodies after the flood %s" % (
        m["before"], m["peak"], m["after"], m["after_reset"], r["bodies_after"]))
    print("  server alive %s, exit %s -> %s" % (r["server_alive"], r["server_exit"], "ok" if r["ok"] else "FAILED"))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--adds", type=int, default=100000, help="ADD commands client A publishes (default 100000)")
    p.add_argument("--period", type=float, default=0.02, help="s between client B's commands")
    p.add_argument("--timeout", type=float, default=5.0, help="client B's reply timeout, s")
    p.add_argument("--running", action="store_true", help="let the server run free during the flood")
    p.add_argument("--quiet", type=float, default=10.0, help="client A stops waiting for replies after this many s "
                   "without one")
    p.add_argument("--max-seconds", type=float, default=1800.0)
    p.add_argument("--build-dir", default=None)
    p.add_argument("--json", action="store_true")
    p.add_argument("--role", choices=["main", "adder"], default="main", help=argparse.SUPPRESS)
    p.add_argument("--url", help=argparse.SUPPRESS)
    p.add_argument("--prefix", help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.role == "adder":
        adder(args.url, args.prefix, args.adds, args.quiet)
        return 0
    result = flood(args)
    print(json.dumps(result) if args.json else "", end="\n" if args.json else "")
    if not args.json:
        print_result(result)
    return 0 if result["ok"] else 1


if __name__ == "__main__":
    sys.exit(main())
