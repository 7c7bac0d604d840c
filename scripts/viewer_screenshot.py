"""Saves a screenshot of the viewer on a scene (the README's docs/viewer.png).

    CONTACTSIM_BUILD_DIR=build .venv/bin/python scripts/viewer_screenshot.py
        [--scene config/scenes/box_pyramid.pbtxt] [--steps 240] [--out docs/viewer.png]

A real server loads the scene and takes --steps steps; the viewer shows the
result in headless chromium, which saves the page as PNG.
"""
import argparse
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "scripts"))
from server_process import ServerProcess  # noqa: E402
from contactsim.viewer.process import ViewerProcess  # noqa: E402

from contactsim.viewer.headless import start_browser, wait_for  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scene", default=str(REPO / "config" / "scenes" / "box_pyramid.pbtxt"))
    p.add_argument("--steps", type=int, default=240)
    p.add_argument("--out", default=str(REPO / "docs" / "viewer.png"))
    p.add_argument("--build-dir", default=None)
    a = p.parse_args()
    with ServerProcess(a.build_dir, scene_text=Path(a.scene).read_text(), tag="VWS", timeout=60) as srv:
        with ViewerProcess(["--lcm-url", srv.url, "--prefix", srv.prefix]) as viewer:
            driver = start_browser(1280, 900)
            try:
                driver.get(viewer.url + "?aa=1")   # multisampled, as on a GPU
                wait_for(driver, "window.contactsimViewer && contactsimViewer.framesDrawn() > 0", timeout=60)
                for _ in range(a.steps // 20):   # in bursts, so that the energy plot has a history
                    srv.client.step(20)
                    time.sleep(0.05)
                wait_for(driver, "contactsimViewer.step() === %d" % srv.client.state().step, timeout=30)
                time.sleep(1.5)   # a STATUS for the panel
                driver.save_screenshot(a.out)
            finally:
                driver.quit()
    print("wrote %s" % a.out)


if __name__ == "__main__":
    main()
