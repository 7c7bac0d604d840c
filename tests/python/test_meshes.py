"""Triangle meshes and heightfields through the real server: added from
vertices, from a file and from a 2-D array, simulated, hit by rays, kept by
snapshots, stepped by the barrier method and refused on bad input
(docs/physics.md, "Triangle meshes and heightfields")."""
import numpy as np
import pytest

import contactsim


def grid(n, cell):
    """An n x n grid of square cells, two triangles each, centred on the origin at z = 0."""
    xs = (np.arange(n + 1) - n / 2) * cell
    vertices = np.array([(x, y, 0.0) for y in xs for x in xs])
    tris = []
    for r in range(n):
        for c in range(n):
            a, b, d, e = r * (n + 1) + c, r * (n + 1) + c + 1, (r + 1) * (n + 1) + c + 1, (r + 1) * (n + 1) + c
            tris += [(a, b, d), (a, d, e)]
    return vertices, np.array(tris)


def test_box_rests_on_a_mesh_and_rays_hit_it(client):
    vertices, tris = grid(20, 0.1)
    floor = client.add_mesh(vertices, tris, friction=0.5)
    box = client.add_box((0.1, 0.1, 0.1), position=(0.03, 0.01, 0.15), restitution=0.0)
    client.step(480)
    body = client.state().bodies[box]
    assert body.position[2] == pytest.approx(0.1, abs=2e-3)
    assert np.linalg.norm(body.linear_velocity) < 1e-2
    hit, ids, points, normals, _ = client.ray_cast([(0.5, 0.5, 1.0)], [(0, 0, -1)], 5.0)
    assert hit[0] and ids[0] == floor
    assert points[0][2] == pytest.approx(0.0, abs=1e-9)
    assert normals[0] == pytest.approx([0.0, 0.0, 1.0])


def test_mesh_from_an_obj_file_is_kept_by_a_snapshot(client, tmp_path):
    vertices, tris = grid(4, 0.5)
    obj = tmp_path / "floor.obj"
    obj.write_text("".join("v %.17g %.17g %.17g\n" % tuple(v) for v in vertices) +
                   "".join("f %d %d %d\n" % tuple(t + 1) for t in tris))
    client.add_mesh(str(obj), scale=2.0)
    ball = client.add_sphere(0.1, position=(0.3, 0.2, 0.3), restitution=0.0)
    client.step(240)
    client.snapshot("with_mesh")
    obj.unlink()  # a restore needs the mesh as it was read, not the file
    client.step(240)
    after = client.state().bodies[ball].position
    client.restore("with_mesh")
    client.step(240)
    assert client.state().bodies[ball].position == pytest.approx(after, abs=1e-12)
    assert after[2] == pytest.approx(0.1, abs=2e-3)


def test_ball_rests_on_a_heightfield(client):
    heights = np.zeros((11, 11))
    heights[5, 5] = 0.2  # a bump at the centre
    client.add_heightfield(heights, 0.1)
    ball = client.add_sphere(0.05, position=(0.3, -0.2, 0.3), restitution=0.0)
    client.step(480)
    assert client.state().bodies[ball].position[2] == pytest.approx(0.05, abs=2e-3)


def test_zero_area_triangles_are_dropped_with_a_warning(client):
    vertices = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (2, 0, 0)]
    with pytest.warns(UserWarning, match="1 triangle"):
        client.add_mesh(vertices, [(0, 1, 2), (0, 1, 3)])


@pytest.mark.parametrize("vertices, indices, says", [
    ([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 3)], "out of range"),
    ([(0, 0, 0), (1, 0, 0), (0, float("nan"), 0)], [(0, 1, 2)], "not finite"),
    ([(0, 0, 0), (1, 0, 0), (2, 0, 0)], [(0, 1, 2)], "zero area"),
])
def test_bad_meshes_add_nothing(client, vertices, indices, says):
    with pytest.raises(contactsim.CommandError) as err:
        client.add_mesh(vertices, indices)
    assert says in str(err.value)
    client.step(1)
    assert len(client.state().bodies) == 0


def test_barrier_rests_a_box_and_a_ball_on_a_mesh(client):
    # Verifies that the barrier method takes a mesh (its contract's
    # triangle_surfaces) and rests a box and a ball dropped on it, above it
    # by less than its activation distance d_hat = 1 mm.
    vertices, tris = grid(20, 0.1)
    client.add_mesh(vertices, tris, friction=0.5)
    client.set_contact_method("barrier")
    box = client.add_box((0.1, 0.1, 0.1), position=(0.03, 0.01, 0.15), restitution=0.0)
    ball = client.add_sphere(0.1, position=(-0.5, 0.3, 0.2), restitution=0.0)
    client.step(240)
    bodies = client.state().bodies
    for body in (bodies[box], bodies[ball]):
        assert 0.1 < body.position[2] < 0.101
        assert np.linalg.norm(body.linear_velocity) < 1e-2


def test_scene_file_with_a_heightfield_and_a_mesh_file(client, tmp_path):
    vertices, tris = grid(2, 1.0)
    (tmp_path / "pad.obj").write_text("".join("v %.17g %.17g %.17g\n" % tuple(v) for v in vertices) +
                                      "".join("f %d %d %d\n" % tuple(t + 1) for t in tris))
    scene = tmp_path / "terrain.pbtxt"
    scene.write_text("""
gravity { z: -9.81 }
bodies { name: "terrain" heightfield { rows: 3 cols: 3 heights: [0, 0, 0, 0, 0, 0, 0, 0, 0]
                                        spacing_x: 1 spacing_y: 1 } }
bodies { name: "pad" mesh { path: "pad.obj" } position { x: 5 z: 0.5 } }
bodies { name: "ball" sphere { radius: 0.1 } position { x: 0.2 y: 0.1 z: 0.5 } material { restitution: 0 } }
bodies { name: "puck" sphere { radius: 0.1 } position { x: 5.1 z: 1.0 } material { restitution: 0 } }
""")
    client.load_scene(scene)
    client.step(480)
    z = sorted(b.position[2] for b in client.state().bodies.values())
    assert z == pytest.approx([0.0, 0.1, 0.5, 0.6], abs=2e-3)


def test_the_viewer_catalog_carries_mesh_and_heightfield_geometry(client, tmp_path):
    from contactsim.viewer.catalog import read_catalog
    vertices, tris = grid(1, 1.0)
    mesh = client.add_mesh(vertices, tris)
    field = client.add_heightfield([[0.0, 0.1, 0.2], [0.3, 0.4, 0.5]], (0.5, 0.25))
    client.snapshot(path=str(tmp_path / "s.snap"))
    shapes = {b["id"]: b["shape"] for b in read_catalog(tmp_path / "s.snap")["bodies"]}
    assert shapes[mesh]["kind"] == "mesh"
    np.testing.assert_allclose(shapes[mesh]["vertices"], vertices.reshape(-1))
    np.testing.assert_array_equal(shapes[mesh]["triangles"], tris.reshape(-1))
    field_shape = dict(shapes[field])
    np.testing.assert_array_equal(field_shape.pop("heights"), [0.0, 0.1, 0.2, 0.3, 0.4, 0.5])
    assert field_shape == {"kind": "heightfield", "rows": 2, "cols": 3, "spacing": [0.5, 0.25]}


def test_journal_recovers_a_mesh_read_from_a_file_that_is_gone(launch, tmp_path):
    vertices, tris = grid(4, 0.5)
    obj = tmp_path / "floor.obj"
    obj.write_text("".join("v %.17g %.17g %.17g\n" % tuple(v) for v in vertices) +
                   "".join("f %d %d %d\n" % tuple(t + 1) for t in tris))
    journal = tmp_path / "journal"
    first = launch(args=("--journal", str(journal)))
    floor = first.client.add_mesh(str(obj))
    ball = first.client.add_sphere(0.1, position=(0.3, 0.2, 0.3), restitution=0.0)
    first.client.step(240)
    rested = first.client.state().bodies[ball].position
    first.kill()
    obj.unlink()  # recovery builds the mesh from the journal's vertices
    second = launch(args=("--journal", str(journal)))
    second.client.step(240)
    bodies = second.client.state().bodies
    assert floor in bodies
    assert bodies[ball].position[2] == pytest.approx(rested[2], abs=1e-6)
