#!/usr/bin/env python3
"""Which LCM build reassembles fragmented messages that arrive out of order?

    .venv/bin/python scripts/lcm_frag.py [--messages 50] [--size 300000] [--json]

Builds scripts/lcm_frag/frag_count.c twice, against Debian's liblcm (the
one the server links, 1.3.1) and against the static liblcm.a that the PyPI
`lcm` wheel in .venv ships (1.5.x), into a temporary folder. Each build
subscribes to a channel on loopback multicast; this script then sends
--messages messages of --size bytes as LCM fragments (the udpm wire format:
"LC03" header, message number, size, offset, fragment number and count,
the channel name in fragment 0) straight from a UDP socket, in five orders:

  in order              every fragment in sequence (the control)
  last fragment first   the final fragment, then the others in sequence
  reversed              every fragment in reverse order
  interleaved pairs     two messages at a time, their fragments alternating
  one fragment lost     every fifth message misses a middle fragment

and counts, per build, the messages delivered intact (right size, right
message number). Out-of-order fragments happen on real networks (several
paths, NIC queues); loopback never reorders, so the orders are made here.
Prints a table, or JSON with --json.
"""
import argparse
import json
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
SOURCE = HERE / "lcm_frag" / "frag_count.c"
GROUP = "239.255.76.67"
FRAGMENT = 64000  # bytes of payload per fragment, as LCM uses close to 64 KiB


def wheel_prefix():
    import lcm  # noqa: PLC0415 - the wheel's package folder
    prefix = Path(lcm.__file__).resolve().parents[1]
    lib = prefix / "lib" / "liblcm.a"
    return prefix if lib.exists() else None


def build(tmp):
    """{name: (binary, version)} of the builds that compile here."""
    pkg = subprocess.run(["pkg-config", "--cflags", "--libs", "lcm"], capture_output=True, text=True)
    glib = subprocess.run(["pkg-config", "--cflags", "--libs", "glib-2.0"], capture_output=True, text=True)
    out = {}
    cc = shutil.which("cc") or shutil.which("gcc")
    if pkg.returncode == 0:
        b = tmp / "frag_count_debian"
        subprocess.run([cc, "-O2", "-o", str(b), str(SOURCE), *pkg.stdout.split()], check=True)
        out["debian liblcm"] = b
    prefix = wheel_prefix()
    if prefix is not None and glib.returncode == 0:
        b = tmp / "frag_count_wheel"
        subprocess.run([cc, "-O2", "-DLCM_STATIC", "-I", str(prefix / "include"), "-o", str(b), str(SOURCE),
                        str(prefix / "lib" / "liblcm.a"), *glib.stdout.split(), "-lpthread"], check=True)
        out["PyPI wheel liblcm.a"] = b
    return out


def fragments(channel, seqno, payload):
    """The udpm fragments of one message, in order."""
    n = (len(payload) + FRAGMENT - 1) // FRAGMENT
    out = []
    for i in range(n):
        chunk = payload[i * FRAGMENT:(i + 1) * FRAGMENT]
        hdr = struct.pack(">IIIIHH", 0x4C433033, seqno, len(payload), i * FRAGMENT, i, n)
        out.append(hdr + (channel.encode() + b"\0" if i == 0 else b"") + chunk)
    return out


def schedule(order, msgs):
    """The datagrams of msgs [(seqno, [fragments])] in the given order, and the messages sent whole."""
    out, whole = [], set()
    if order == "interleaved pairs":
        for k in range(0, len(msgs), 2):
            pair = msgs[k:k + 2]
            for i in range(max(len(f) for _, f in pair)):
                for _, f in pair:
                    if i < len(f):
                        out.append(f[i])
            whole.update(s for s, _ in pair)
        return out, whole
    for idx, (seqno, frags) in enumerate(msgs):
        if order == "in order":
            out += frags
        elif order == "last fragment first":
            out += [frags[-1]] + frags[:-1]
        elif order == "reversed":
            out += frags[::-1]
        elif order == "one fragment lost":
            if idx % 5 == 4:
                out += frags[:1] + frags[2:]
                continue
            out += frags
        whole.add(seqno)
    return out, whole


ORDERS = ("in order", "last fragment first", "reversed", "interleaved pairs", "one fragment lost")


def run_order(binary, port, order, messages, size, seq0):
    url = "udpm://%s:%d?ttl=0&recv_buf_size=8388608" % (GROUP, port)
    channel = "FRAG_%d" % os.getpid()
    msgs = []
    for k in range(messages):
        number = seq0 + k
        payload = struct.pack(">I", number) + bytes([number & 0xFF]) * (size - 4)
        msgs.append((number, fragments(channel, number, payload)))
    datagrams, whole = schedule(order, msgs)
    rx = subprocess.Popen([str(binary), url, channel, "2"], stdout=subprocess.PIPE, text=True)
    ready = rx.stdout.readline().split()
    time.sleep(0.5)  # LCM's receive thread joins the group after lcm_subscribe returns
    tx = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    tx.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
    tx.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 1)
    for i, d in enumerate(datagrams):
        tx.sendto(d, (GROUP, port))
        if i % 8 == 7:
            time.sleep(0.002)  # the receive buffer is not the subject here
    tx.close()
    out, _ = rx.communicate(timeout=60)
    got = set()
    for line in out.splitlines():
        n, number = (int(x) for x in line.split())
        if n == size:
            got.add(number)
    return dict(version=ready[1] if len(ready) > 1 else "?", sent_whole=len(whole), delivered=len(got & whole),
                extra=len(got - whole))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--messages", type=int, default=50)
    p.add_argument("--size", type=int, default=300000, help="bytes per message (default 300000: 5 fragments)")
    p.add_argument("--port", type=int, default=9700 + os.getpid() % 90)
    p.add_argument("--json", action="store_true")
    args = p.parse_args(argv)
    tmp = Path(tempfile.mkdtemp(prefix="contactsim-lcmfrag-"))
    try:
        builds = build(tmp)
        results = {}
        for name, binary in builds.items():
            results[name] = {}
            for k, order in enumerate(ORDERS):
                results[name][order] = run_order(binary, args.port, order, args.messages, args.size, 1000 * (k + 1))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if args.json:
        print(json.dumps(dict(messages=args.messages, size=args.size, fragment=FRAGMENT, results=results)))
        return 0
    names = list(results)
    versions = [next(iter(results[n].values()))["version"] for n in names]
    print("%d messages of %d bytes (%d fragments each), delivered intact / sent whole:" % (
        args.messages, args.size, (args.size + FRAGMENT - 1) // FRAGMENT))
    print("| order | " + " | ".join("%s %s" % (n, v) for n, v in zip(names, versions)) + " |")
    print("|---|" + "---|" * len(names))
    for order in ORDERS:
        print("| %s | " % order + " | ".join("%d / %d" % (results[n][order]["delivered"], results[n][order]["sent_whole"])
                                            for n in names) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
