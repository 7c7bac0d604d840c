"""Frames per second of the viewer in headless chromium on a large scene,
and the latency the bridge adds from STATE to screen (BENCHMARKS.md, "Viewer").

    CONTACTSIM_BUILD_DIR=build .venv/bin/python bench/scripts/viewer_bench.py [--scene config/scenes/sphere_pile.pbtxt]
                                                                        [--seconds 10] [--method impulse]

A real server runs the scene in REALTIME mode; a raw LCM subscriber stamps
each STATE's arrival (wall clock, this host), the page stamps the moment a
frame arrives and the moment it drew it (performance.timeOrigin + now, after
the render call); the latencies are the differences. Steps the bridge skipped (latest
only) are not drawn and not counted.
"""
import argparse
import os
import statistics
import struct
import sys
import threading
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "scripts"))
from server_process import ServerProcess  # noqa: E402
from contactsim.viewer.process import ViewerProcess  # noqa: E402

import lcm  # noqa: E402

from contactsim.viewer.headless import start_browser, wait_for  # noqa: E402


def stamp_states(url, channel, arrivals, stop):
    """Records wall-clock ms of each STATE's arrival by step (the step is at byte 16 of state_t)."""
    lc = lcm.LCM(url)
    lc.subscribe(channel, lambda ch, data: arrivals.setdefault(struct.unpack_from(">q", data, 16)[0],
                                                               time.time() * 1000.0))
    while not stop.is_set():
        lc.handle_timeout(20)


async def _bridge_only(url, seconds, log):
    """A WebSocket client that acks each POSES frame at once: what the bridge
    alone adds, without a browser's rendering in the way."""
    import aiohttp
    async with aiohttp.ClientSession() as session:
        async with session.ws_connect(url.replace("http", "ws", 1) + "ws", max_msg_size=0) as ws:
            end = time.monotonic() + seconds
            while time.monotonic() < end:
                msg = await ws.receive(timeout=seconds)
                if msg.type == aiohttp.WSMsgType.BINARY and struct.unpack_from("<d", msg.data)[0] == 1.0:
                    log.append((struct.unpack_from("<d", msg.data, 8)[0], time.time() * 1000.0))
                    await ws.send_str('{"cmd": "ack"}')


def bridge_only(url, seconds):
    """[(step, epoch ms received)] over `seconds`."""
    import asyncio
    log = []
    asyncio.run(_bridge_only(url, seconds, log))
    return log


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
    p.add_argument("--query", default="", help="appended to the page URL, e.g. ?aa=0 (no multisampling)")
    p.add_argument("--window", type=int, nargs=2, default=(1280, 800), metavar=("W", "H"),
                   help="browser window size, px")
    p.add_argument("--build-dir", default=None)
    a = p.parse_args()
    with ServerProcess(a.build_dir, scene_text=Path(a.scene).read_text(), tag="VWB") as srv:
        c = srv.client
        c.set_contact_method(a.method)
        arrivals, stop = {}, threading.Event()
        threading.Thread(target=stamp_states, args=(srv.url, srv.client.channels["STATE"], arrivals, stop),
                         daemon=True).start()
        with ViewerProcess(["--lcm-url", srv.url, "--prefix", srv.prefix]) as viewer:
            driver = start_browser(*a.window)
            try:
                driver.get(viewer.url + a.query)
                wait_for(driver, "window.contactsimViewer && contactsimViewer.framesDrawn() > 0", timeout=60)
                c.set_mode("realtime")
                c.resume()
                time.sleep(2.0)   # past the first frames (shader compilation, layout)
                fps, drawn = measure(driver, a.seconds)
                log = driver.execute_script("return contactsimViewer.frameLog()")
                bodies = len(driver.execute_script("return contactsimViewer.bodies()"))
                update_ms = driver.execute_script("return contactsimViewer.updateMs()")
            finally:
                driver.quit()
            bridge_log = bridge_only(viewer.url, a.seconds)
        status = c.status()
        stop.set()
    drawn_log = [(arrivals[int(s)], got, shown) for s, got, shown in log if int(s) in arrivals]
    drawn_log = drawn_log[len(drawn_log) // 10:]   # the warm-up tenth, in drawing order, is left out
    if not drawn_log:
        sys.exit("no STATE was drawn while measuring")
    to_page = sorted(got - t for t, got, _ in drawn_log)
    bridge = [got - arrivals[int(s)] for s, got in bridge_log if int(s) in arrivals]
    bridge = sorted(bridge[len(bridge) // 10:])
    lat = sorted(shown - t for t, _, shown in drawn_log)
    print("scene %s: %d bodies drawn, method %s, server rtf %.2f (%.0f steps/s)" % (
        Path(a.scene).name, bodies, a.method, status.real_time_factor, status.step_rate))
    print("headless chromium (SwiftShader, %dx%d%s): %.1f frames/s rendered, %.1f STATE frames/s drawn" % (
        a.window[0], a.window[1], ", " + a.query if a.query else "", fps, drawn))
    print("page: %.1f ms median to apply a frame to the scene graph (instance matrices, contacts)" % (
        statistics.median(update_ms[1:] or update_ms)))
    print("load average during the run: %.1f on %d cores" % (os.getloadavg()[0], os.cpu_count()))
    p95 = lambda v: v[round(0.95 * (len(v) - 1))]  # noqa: E731
    print("STATE -> WebSocket client acking at once (the bridge alone): median %.1f ms, p95 %.1f ms, "
          "%.0f frames/s" % (statistics.median(bridge), p95(bridge), len(bridge_log) / a.seconds))
    print("STATE -> page (bridge, WebSocket, the page's busy main thread): median %.1f ms, p95 %.1f ms" % (
        statistics.median(to_page), p95(to_page)))
    print("STATE -> screen (drawn): median %.1f ms, p95 %.1f ms over %d drawn STATEs" % (
        statistics.median(lat), p95(lat), len(lat)))


if __name__ == "__main__":
    main()
