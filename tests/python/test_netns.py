"""The server and a Python controller in two network namespaces joined by a
veth pair, talking LCM over multicast with ttl=1 as they would across a
LAN: the controller adds a body, steps the world, reads STATE, and runs a
few lockstep steps. Skipped unless root with a working `ip netns`.

The namespaces, the veth pair and their link-local addresses
(169.254.76.1/30 and .2) are made by the test and deleted afterwards;
nothing leaves them. Each side needs a multicast route (224.0.0.0/4 on its
veth end): without one the kernel has no interface for the group and LCM
fails to open (the server says "cannot open LCM ... no multicast route?").
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import textwrap

import pytest

from conftest import CONFIG, REPO, SERVER_BIN

URL = "udpm://239.255.76.67:7667?ttl=1&recv_buf_size=8388608"
TAG = "cs%d" % (os.getpid() % 100000)
NS_SERVER, NS_CLIENT = TAG + "s", TAG + "c"
VETH_SERVER, VETH_CLIENT = TAG + "vs", TAG + "vc"   # interface names: at most 15 characters

CONTROLLER = textwrap.dedent("""
    import json, sys
    import contactsim
    url, prefix = sys.argv[1], sys.argv[2]
    with contactsim.Client(url=url, prefix=prefix, timeout=10.0) as c:
        st = c.wait_for_server(timeout=20.0)
        ball = c.add_sphere(0.1, position=(0, 0, 1.0), mass=1.0)
        r = c.step(24)
        z = float(c.state().bodies[ball].position[2])
        with contactsim.Controller(c, lambda s: {ball: (0.0, 0.0, 9.81)}) as ctl:
            c.set_mode("lockstep")
            c.resume()
            ctl.wait_for_step(r.step + 20, timeout=30.0)
            c.pause()
        last = c.state()
        print(json.dumps(dict(version=st.version, ball=ball, step=r.step, z=z, lockstep_step=last.step,
                              digest=last.input_digest, bodies=sorted(last.bodies))), flush=True)
""")


def sh(*cmd, ns=None):
    full = (["ip", "netns", "exec", ns] if ns else []) + list(cmd)
    return subprocess.run(full, check=True, capture_output=True, text=True)


@pytest.fixture
def namespaces():
    if os.geteuid() != 0 or shutil.which("ip") is None:
        pytest.skip("needs root and iproute2 (ip netns)")
    try:
        sh("ip", "netns", "add", NS_SERVER)
    except subprocess.CalledProcessError as e:
        pytest.skip("ip netns is not available here: %s" % e.stderr.strip())
    try:
        sh("ip", "netns", "add", NS_CLIENT)
        sh("ip", "link", "add", VETH_SERVER, "netns", NS_SERVER, "type", "veth", "peer", "name", VETH_CLIENT,
           "netns", NS_CLIENT)
        for ns, dev, addr in ((NS_SERVER, VETH_SERVER, "169.254.76.1/30"), (NS_CLIENT, VETH_CLIENT, "169.254.76.2/30")):
            sh("ip", "link", "set", "lo", "up", ns=ns)
            sh("ip", "addr", "add", addr, "dev", dev, ns=ns)
            sh("ip", "link", "set", dev, "up", ns=ns)
            sh("ip", "route", "add", "224.0.0.0/4", "dev", dev, ns=ns)
        yield
    finally:
        for ns in (NS_SERVER, NS_CLIENT):
            subprocess.run(["ip", "netns", "del", ns], capture_output=True)


def test_server_and_controller_in_two_namespaces_over_a_veth_pair(namespaces, tmp_path):
    if not SERVER_BIN.exists():
        pytest.skip("%s is not built" % SERVER_BIN)
    scene = tmp_path / "netns-scene.pbtxt"
    scene.write_text('gravity { z: -9.81 }\nbodies { name: "ground" plane { normal { z: 1 } offset: 0 } }\n')
    prefix = "NETNS%d" % os.getpid()
    log = open(tmp_path / "server.log", "wb")
    server = subprocess.Popen(["ip", "netns", "exec", NS_SERVER, str(SERVER_BIN), "--config", str(CONFIG),
                               "--scene", str(scene), "--lcm-url", URL, "--prefix", prefix, "--mode", "free_run",
                               "--paused", "--no-live-line"], stdout=log, stderr=subprocess.STDOUT,
                              stdin=subprocess.DEVNULL)
    try:
        env = dict(os.environ, PYTHONPATH=str(REPO / "clients" / "python"))
        out = subprocess.run(["ip", "netns", "exec", NS_CLIENT, sys.executable, "-c", CONTROLLER, URL, prefix],
                             capture_output=True, text=True, timeout=120, env=env)
        assert out.returncode == 0, "controller failed:\n%s\n%s\nserver log:\n%s" % (
            out.stdout, out.stderr, (tmp_path / "server.log").read_text(errors="replace"))
        r = json.loads(out.stdout.strip().splitlines()[-1])
        print("\nnetns: %s" % r)
        assert r["step"] == 24 and r["bodies"] == [1, r["ball"]]
        assert r["z"] < 1.0                       # it fell for 24 steps
        assert r["lockstep_step"] >= r["step"] + 20
        assert r["digest"] != 0                   # the controller's inputs were applied
    finally:
        server.send_signal(signal.SIGINT)
        try:
            rc = server.wait(10)
        except subprocess.TimeoutExpired:
            server.kill()
            rc = server.wait()
        log.close()
    assert rc == 0, (tmp_path / "server.log").read_text(errors="replace")
