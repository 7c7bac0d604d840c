"""PyBullet's rayTestBatch on the world and rays that contactsim-bench-rays
writes with --dump (BENCHMARKS.md, "Ray casts"): the same shapes and poses,
one thread, every call of at most MAX_RAY_INTERSECTION_BATCH_SIZE rays;
prints the median ms of --repeat batches and how many rays hit (beside
contactsim-bench-rays' count for the same rays). PyBullet's mesh and box
shapes keep their default margins, so its hits differ from the exact ones
by up to those margins.

    build/bin/contactsim-bench-rays --dump /tmp/rays.json
    .venv/bin/python bench/scripts/ray_bench_pybullet.py /tmp/rays.json
"""
import argparse
import json
import statistics
import time

import pybullet as p


def shape_of(b):
    if b["shape"] == "sphere":
        return p.createCollisionShape(p.GEOM_SPHERE, radius=b["radius"])
    if b["shape"] == "box":
        return p.createCollisionShape(p.GEOM_BOX, halfExtents=b["half_extents"])
    if b["shape"] == "capsule":
        return p.createCollisionShape(p.GEOM_CAPSULE, radius=b["radius"], height=2 * b["half_length"])
    if b["shape"] == "convex":
        return p.createCollisionShape(p.GEOM_MESH, vertices=b["vertices"])
    return p.createCollisionShape(p.GEOM_PLANE, planeNormal=[0, 0, 1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dump")
    ap.add_argument("--repeat", type=int, default=9)
    a = ap.parse_args()
    data = json.load(open(a.dump))
    p.connect(p.DIRECT)
    ids = {}
    for b in data["bodies"]:
        w, x, y, z = b["orientation"]
        uid = p.createMultiBody(baseMass=0, baseCollisionShapeIndex=shape_of(b), basePosition=b["position"],
                                baseOrientation=[x, y, z, w])
        ids[uid] = b["id"]
    froms = [r[0] for r in data["rays"]]
    tos = [r[1] for r in data["rays"]]
    out = None
    ms = []
    for _ in range(a.repeat):
        # rayTestBatch takes at most p.MAX_RAY_INTERSECTION_BATCH_SIZE rays a call
        t0 = time.thread_time()  # CPU time: the machine may be shared
        out = []
        step = p.MAX_RAY_INTERSECTION_BATCH_SIZE
        for i in range(0, len(froms), step):
            out += p.rayTestBatch(froms[i:i + step], tos[i:i + step], numThreads=1)
        ms.append(1000 * (time.thread_time() - t0))
    hits = sum(1 for r in out if r[0] >= 0)
    print("PyBullet rayTestBatch, %d rays against %d bodies (%d hit), numThreads=1: median %.3f ms thread CPU time of %d batches"
          % (len(froms), len(data["bodies"]), hits, statistics.median(ms), a.repeat))


if __name__ == "__main__":
    main()
