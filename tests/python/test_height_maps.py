"""Heightfields from height map files through the real server: a 16-bit
PNG and a raw file give the grid their samples say (docs/physics.md,
"Heightfields from height map files"), from the client, both CLIs and a
journal that outlives the file; bad files are refused in
bad_input_cases.py."""
import subprocess

import numpy as np
import pytest

from conftest import BUILD
from height_maps import heights_of, write_png, write_raw
from test_cli import cli

from contactsim.viewer.catalog import read_catalog

CTL = BUILD / "bin" / "contactsim-ctl"
# 3 rows x 4 cols: 258 = 0x0102 tells byte orders apart, 0 and 65535 the ends
SAMPLES = np.array([[0, 258, 65535, 1000], [30000, 12345, 65534, 7], [40000, 20000, 10000, 5000]])
SCALE, OFFSET = 2.0, -0.5   # m


def _heights(client, body, tmp_path):
    """(rows, cols, heights) of a body as the server holds it (its snapshot)."""
    path = tmp_path / ("h%d.snap" % body)
    client.snapshot(path=str(path))
    shape = next(b["shape"] for b in read_catalog(path)["bodies"] if b["id"] == body)
    return shape["rows"], shape["cols"], np.array(shape["heights"]).reshape(shape["rows"], shape["cols"])


# Verifies that a PNG and a raw file of the same samples give the heights
# offset + scale s / 65535 with the file's first row at the largest y, and
# that a ray cast meets the grid there: sample (1, 2) of the file is the
# grid's row 1 at x = (2 - 1.5) dx, y = (1 - 1) dy.
def test_png_and_raw_files_give_the_grid_of_their_samples(client, tmp_path):
    want = heights_of(SAMPLES, SCALE, OFFSET)
    png = client.add_heightfield(write_png(tmp_path / "t.png", SAMPLES), (0.5, 0.25), scale=SCALE, offset=OFFSET)
    raw = client.add_heightfield(write_raw(tmp_path / "t.raw", SAMPLES), (0.5, 0.25), rows=3, cols=4, scale=SCALE,
                                 offset=OFFSET, position=(10, 0, 0))
    for body in (png, raw):
        rows, cols, heights = _heights(client, body, tmp_path)
        assert (rows, cols) == (3, 4)
        np.testing.assert_allclose(heights, want, rtol=0, atol=1e-15)
    with pytest.raises(ValueError, match="for a height map file"):
        client.add_heightfield(want, (0.5, 0.25), scale=SCALE)   # an array's heights are metres already
    client.step(1)   # ray casts see the bodies of the last step
    hits = client.ray_cast([(0.25, 0.0, 5.0), (10.25, 0.0, 5.0)], [(0, 0, -1)] * 2, 10.0)
    assert list(hits.body_ids) == [png, raw]
    np.testing.assert_allclose(hits.points[:, 2], [OFFSET + SCALE * (65534 / 65535)] * 2, atol=1e-12)


# Verifies that the journal keeps the heights read, not the path: a server
# recovering from it rebuilds the heightfield after the file is gone.
def test_journal_recovers_a_heightfield_whose_file_is_gone(launch, tmp_path):
    path = write_png(tmp_path / "gone.png", SAMPLES)
    journal = tmp_path / "journal"
    first = launch(args=("--journal", str(journal)))
    field = first.client.add_heightfield(path, 0.3, scale=SCALE, offset=OFFSET)
    first.client.step(1)
    first.kill()
    (tmp_path / "gone.png").unlink()
    second = launch(args=("--journal", str(journal)))
    second.client.step(1)
    assert field in second.client.state().bodies
    _, _, heights = _heights(second.client, field, tmp_path)
    np.testing.assert_allclose(heights, heights_of(SAMPLES, SCALE, OFFSET), rtol=0, atol=1e-15)


# Verifies that both command-line clients add a heightfield from a file
# with its spacing, size, scale and offset, and report a bad file's refusal.
def test_both_clis_add_a_heightfield_from_a_file(server, tmp_path):
    raw = write_raw(tmp_path / "t.raw", SAMPLES)
    r = cli(server, "add", "heightfield", raw, "--rows", "3", "--cols", "4", "--scale", "2", "--offset", "-0.5",
            "--spacing", "0.5", "0.25")
    assert r.returncode == 0, r.stdout + r.stderr
    py_body = int(r.stdout.strip())
    np.testing.assert_allclose(_heights(server.client, py_body, tmp_path)[2], heights_of(SAMPLES, SCALE, OFFSET),
                               atol=1e-15)
    r = cli(server, "add", "heightfield", raw, "--rows", "4", "--cols", "4")
    assert r.returncode != 0 and "24 bytes" in r.stderr, r.stdout + r.stderr
    if not CTL.exists():
        pytest.skip("%s is not built" % CTL)
    args = [str(CTL), "--lcm-url", server.url, "--prefix", server.prefix]
    r = subprocess.run(args + ["add", "heightfield", write_png(tmp_path / "t.png", SAMPLES), "--scale", "2",
                               "--offset", "-0.5", "--spacing", "0.5", "0.25"],
                       capture_output=True, text=True, timeout=30)
    assert r.returncode == 0, r.stdout + r.stderr
    server.client.step(1)
    bodies = server.client.state().bodies
    assert len(bodies) == 2
    ctl_body = max(bodies)
    np.testing.assert_allclose(_heights(server.client, ctl_body, tmp_path)[2], heights_of(SAMPLES, SCALE, OFFSET),
                               atol=1e-15)
