"""Frames per second of the viewer in headless chromium on a large scene,
and the latency the bridge adds from STATE to screen (BENCHMARKS.md, "Viewer").

    CONTACTSIM_BUILD_DIR=build .venv/bin/python scripts/viewer_bench.py [--scene config/scenes/sphere_pile.pbtxt]
                                                                        [--seconds 10] [--method impulse]

A real server runs the scene in REALTIME mode; a raw LCM subscriber stamps
each STATE's arrival (wall clock, this host), the page stamps the moment it
drew each step (performance.timeOrigin + now, after the render call), and the
latency of a drawn step is the difference. Steps the bridge skipped (latest
only) are not drawn and not counted.
"""
import argparse
import statistics
import struct
import sys
import threading
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "scripts"))
from server_process import ServerProcess  # noqa: E402
from viewer_process import ViewerProcess  # noqa: E402

import lcm  # noqa: E402

from contactsim.viewer.headless import start_browser, wait_for  # noqa: E402


def stamp_states(url, channel, arrivals, stop):
    """Records wall-clock ms of each STATE's arrival by step (the step is at byte 16 of state_t)."""
    lc = lcm.LCM(url)
    lc.subscribe(channel, lambda ch, data: arrivals.setdefault(struct.unpack_from(">q", data, 16)[0],
                                                               time.time() * 1000.0))
    while not stop.is_set():
        lc.handle_timeout(20)


def measure(driver, seconds):
    """(render fps, pose frames drawn per second) over `seconds`."""
    r0, f0 = driver.execute_script("return [contactsimViewer.renders(), contactsimViewer.framesDrawn()]")
    t0 = time.monotonic()
    time.sleep(seconds)
    r1, f1 = driver.execute_script("return [contactsimViewer.renders(), contactsimViewer.framesDrawn()]")
    dt = time.monotonic() - t0
    return (r1 - r0) / dt, (f1 - f0) / dt


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scene", default=str(REPO / "config" / "scenes" / "sphere_pile.pbtxt"))
    p.add_argument("--seconds", type=float, default=10.0)
    p.add_argument("--method", default="impulse")
    p.add_argument("--build-dir", default=None)
    a = p.parse_args()
    with ServerProcess(a.build_dir, scene_text=Path(a.scene).read_text(), tag="VWB") as srv:
        c = srv.client
        c.set_contact_method(a.method)
        arrivals, stop = {}, threading.Event()
        threading.Thread(target=stamp_states, args=(srv.url, srv.prefix + "_STATE", arrivals, stop),
                         daemon=True).start()
        with ViewerProcess(["--lcm-url", srv.url, "--prefix", srv.prefix]) as viewer:
            driver = start_browser()
            try:
                driver.get(viewer.url)
                wait_for(driver, "window.contactsimViewer && contactsimViewer.framesDrawn() > 0", timeout=60)
                c.set_mode("realtime")
                c.resume()
                time.sleep(2.0)   # past the first frames (shader compilation, layout)
                fps, drawn = measure(driver, a.seconds)
                log = driver.execute_script("return contactsimViewer.frameLog()")
                bodies = len(driver.execute_script("return contactsimViewer.bodies()"))
            finally:
                driver.quit()
        status = c.status()
        stop.set()
    lat = sorted(t - arrivals[int(s)] for s, t in log if int(s) in arrivals)
    lat = lat[len(lat) // 10:]   # skip the warm-up tenth
    print("scene %s: %d bodies drawn, method %s, server rtf %.2f (%.0f steps/s)" % (
        Path(a.scene).name, bodies, a.method, status.real_time_factor, status.step_rate))
    print("headless chromium (SwiftShader): %.1f frames/s rendered, %.1f STATE frames/s drawn" % (fps, drawn))
    print("STATE -> screen: median %.1f ms, p95 %.1f ms over %d drawn STATEs" % (
        statistics.median(lat), lat[int(0.95 * (len(lat) - 1))], len(lat)))


if __name__ == "__main__":
    main()
