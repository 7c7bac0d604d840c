"""Stopping distance of a sliding 0.2 m, 1 kg cube (mu 0.5, 3 m/s) per method and
heading, through the Python client against a real server (dt 1/240), as the
friction rows of the method pages (docs/methods/NAME.md, "Friction"; the
scenes: docs/physics.md, "Coulomb friction in every method").

    .venv/bin/python scripts/friction_table.py . [settle]

"settle": the cube rests 0.2 s and is then launched; otherwise it is placed
flush on the ground with its velocity (the barrier method's hop,
docs/methods/barrier.md, "Pairs placed touching").
"""
import math, os, subprocess, sys, time
from pathlib import Path
REPO = Path(sys.argv[1]); BUILD = REPO / "build"
sys.path.insert(0, str(REPO / "clients" / "python"))
import contactsim
settle = len(sys.argv) > 2 and sys.argv[2] == "settle"
port = 9900 + os.getpid() % 50
url = "udpm://239.255.76.67:%d?ttl=0&recv_buf_size=8388608" % port
prefix = "FRIC%d" % os.getpid()
import tempfile
scene = Path(tempfile.mkdtemp()) / "empty.pbtxt"; scene.write_text("gravity { z: -9.81 }\n")
proc = subprocess.Popen([str(BUILD / "bin/contactsim-server"), "--config", str(REPO / "config/server.pbtxt"),
                         "--scene", str(scene), "--lcm-url", url, "--mode", "free_run", "--paused",
                         "--no-live-line", "--prefix", prefix], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
try:
    with contactsim.Client(url=url, prefix=prefix, timeout=20) as sim:
        sim.wait_for_server(timeout=20)
        methods = [("impulse", {}), ("penalty", {}), ("xpbd", {}), ("lcp", {"solver": "pgs"}),
                   ("lcp", {"solver": "lemke"}), ("barrier", {})]
        mu, v0, g = 0.5, 3.0, 9.81
        print("analytic %.3f m, %s" % (v0 * v0 / (2 * mu * g), "settled 0.2 s then launched" if settle else "placed flush with v0"))
        for name, params in methods:
            row = []
            for deg in (0, 30, 45, 60):
                sim.reset()
                sim.set_contact_method(name, **params)
                sim.add_plane((0, 0, 1), 0.0, restitution=0.0, friction=mu)
                a = math.radians(deg); d = (math.cos(a), math.sin(a), 0.0)
                vel = (0, 0, 0) if settle else tuple(v0 * c for c in d)
                box = sim.add_box((0.1, 0.1, 0.1), position=(0, 0, 0.1), mass=1.0, velocity=vel,
                                  restitution=0.0, friction=mu)
                if settle:
                    sim.step(48)
                    sim.set_velocity(box, tuple(v0 * c for c in d), (0, 0, 0))
                x0 = sim.state().bodies[box].position if settle else (0.0, 0.0, 0.1)
                sim.step(360)
                x = sim.state().bodies[box].position
                row.append((x[0] - x0[0]) * d[0] + (x[1] - x0[1]) * d[1])
            label = name + ("_" + params["solver"] if params else "")
            print("| %-10s | " % label + " | ".join("%.3f" % r for r in row) + " |", flush=True)
finally:
    proc.terminate(); proc.wait()
