"""Static triangle meshes and heightfields, commands of the Client on
<prefix>_BODY_CMD (docs/protocol.md; docs/physics.md, "Triangle meshes and
heightfields"). Both are static bodies: they never move, and what touches
them collides with their triangles' faces, edges and vertices.
"""
import os
import warnings

import numpy as np

from . import body_cmd_t
from ._fields import vector as _vec
from .filters import fill_filter


class SurfaceCommands:
    """Mixin of Client: needs its ``_body``, ``_material`` and ``_send``."""

    def add_mesh(self, path_or_vertices, indices=None, *, scale=1.0, position=(0, 0, 0),
                 orientation=(1, 0, 0, 0), restitution=None, friction=None, name="",
                 collision_category=None, collision_mask=None, collision_group=None):
        """Adds a static triangle mesh; returns its id.

        Either a mesh file's path (OBJ, STL, PLY, DAE, ...: read by the
        server, relative paths against its model paths) or vertices (N x 3,
        m, body frame) with indices (M x 3 or 3 M, counter-clockwise seen
        from the front: bodies are pushed out of the front). scale (> 0)
        multiplies the vertices. Triangles of zero area are dropped, and the
        reply's message says how many (docs/physics.md, "Triangle meshes and
        heightfields")."""
        m = self._body(body_cmd_t.ADD)
        fill_filter(m, collision_category, collision_mask, collision_group)
        m.shape = body_cmd_t.MESH
        if isinstance(path_or_vertices, (str, os.PathLike)):
            if indices is not None:
                raise ValueError("indices are for vertices, not a mesh file")
            m.mesh_path = os.fspath(path_or_vertices)
        else:
            verts = np.asarray(path_or_vertices, dtype=np.float64)
            if verts.ndim != 2 or verts.shape[1] != 3:
                raise ValueError("vertices must be an N x 3 array, got shape %s" % (verts.shape,))
            if indices is None:
                raise ValueError("vertices need indices (three per triangle)")
            idx = np.asarray(indices).reshape(-1)
            if idx.size and not np.issubdtype(idx.dtype, np.integer):
                raise ValueError("indices must be integers, got %s" % idx.dtype)
            m.num_points = len(verts)
            m.points = verts.tolist()
            m.num_mesh_indices = int(idx.size)
            m.mesh_indices = [int(i) for i in idx]
        m.mesh_scale = float(scale)
        m.position = _vec(position, 3, "position")
        m.orientation = _vec(orientation, 4, "orientation")
        m.fixed = True
        self._material(m, restitution, friction)
        m.name = name
        reply = self._send("BODY_CMD", m)
        if "dropped" in reply.message:
            warnings.warn(reply.message)
        return reply.ids[0]

    def add_heightfield(self, path_or_heights, spacing, *, rows=0, cols=0, scale=1.0, offset=0.0,
                        position=(0, 0, 0), orientation=(1, 0, 0, 0), restitution=None, friction=None, name="",
                        collision_category=None, collision_mask=None, collision_group=None):
        """Adds a static heightfield; returns its id.

        Either heights, a 2-D array (rows along body y, columns along body
        x, m, at least 2 x 2), or a height map file's path, which the server
        reads (a relative path against its model paths): a 16-bit greyscale
        PNG, or a raw file of ``rows`` x ``cols`` little-endian uint16
        samples. A file's first row is the grid's last (largest y, an image
        seen from above), and its sample s (0 to 65535) is the height
        ``offset + scale * s / 65535`` (m). spacing: one number or (dx, dy),
        m. The grid is centred on position; each cell is two triangles
        (docs/physics.md, "Triangle meshes and heightfields")."""
        sp = np.broadcast_to(np.asarray(spacing, dtype=np.float64), (2,))
        m = self._body(body_cmd_t.ADD)
        fill_filter(m, collision_category, collision_mask, collision_group)
        m.shape = body_cmd_t.HEIGHTFIELD
        if isinstance(path_or_heights, (str, os.PathLike)):
            m.height_path = os.fspath(path_or_heights)
            m.height_rows, m.height_cols = int(rows), int(cols)
            m.height_scale, m.height_offset = float(scale), float(offset)
        else:
            if (rows, cols, scale, offset) != (0, 0, 1.0, 0.0):
                raise ValueError("rows, cols, scale and offset are for a height map file, not heights")
            h = np.asarray(path_or_heights, dtype=np.float64)
            if h.ndim != 2:
                raise ValueError("heights must be a 2-D array, got shape %s" % (h.shape,))
            m.height_rows, m.height_cols = int(h.shape[0]), int(h.shape[1])
            m.num_heights = int(h.size)
            m.heights = [float(v) for v in h.reshape(-1)]
        m.height_spacing = [float(sp[0]), float(sp[1])]
        m.position = _vec(position, 3, "position")
        m.orientation = _vec(orientation, 4, "orientation")
        m.fixed = True
        self._material(m, restitution, friction)
        m.name = name
        return self._send("BODY_CMD", m).ids[0]
