"""The mesh files of the robot models' visuals, served to the page.

The page asks for /meshes/<folder>/<file>: <folder> numbers one of the
folders that hold a mesh file the catalog names (the resolved paths the
server read), <file> a path inside it (a Collada file's textures sit beside
it or below). Nothing else is served: a path that leaves its folder (``..``,
an absolute path, a symbolic link out of it), a folder no model names, or a
file that is not a mesh, material or texture is refused, so the bridge never
becomes a reader of the host's files.
"""
import os

# meshes the page loads (OBJ, STL, Collada), OBJ's materials and textures
SERVED_EXTENSIONS = frozenset((".obj", ".stl", ".dae", ".mtl", ".png", ".jpg", ".jpeg", ".tga", ".bmp", ".gif"))
URL_PREFIX = "/meshes/"


class MeshFiles:
    def __init__(self):
        self.folders = []     # real paths; a folder's number is its index

    def add_urls(self, catalog):
        """Gives every mesh visual of the catalog's models a "url" (None when
        its file is not one the page may load); from now on only their
        folders are served."""
        self.folders = []
        for model in catalog.get("models", []):
            for link in model["links"]:
                for v in link["visuals"]:
                    if v["kind"] == "mesh":
                        v["url"] = self._url(v.get("mesh_path", ""))

    def _url(self, path):
        if not os.path.isabs(path) or os.path.splitext(path)[1].lower() not in SERVED_EXTENSIONS:
            return None
        real = os.path.realpath(path)
        folder = os.path.dirname(real)
        if folder not in self.folders:
            self.folders.append(folder)
        return "%s%d/%s" % (URL_PREFIX, self.folders.index(folder), os.path.basename(real))

    def resolve(self, folder, relative):
        """The file to serve for /meshes/<folder>/<relative>, or None."""
        if not (folder.isascii() and folder.isdigit()) or int(folder) >= len(self.folders):
            return None
        root = self.folders[int(folder)]
        if not relative or os.path.isabs(relative) or "\0" in relative:
            return None
        if os.path.splitext(relative)[1].lower() not in SERVED_EXTENSIONS:
            return None
        real = os.path.realpath(os.path.join(root, relative))
        if os.path.commonpath([root, real]) != root or not os.path.isfile(real):
            return None
        return real
