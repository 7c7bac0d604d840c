"""The robot models of a snapshot file (service/proto/model.proto,
ModelRecord): each link's body, its frame in that body and its visual
elements, and the joints' names and world ids, as plain dicts for the page
(docs/viewer.md, "Robot models")."""

# model::GeometryType (service/model/model_description.h), as ModelGeometry.type holds it
GEOMETRY_KINDS = {0: "box", 1: "sphere", 2: "cylinder", 3: "capsule", 4: "mesh"}

_POSE = {1: ("position", "double", True), 2: ("orientation", "double", True)}
_GEOMETRY = {1: ("type", "int", False), 2: ("box_size", "double", True), 3: ("radius", "double", False),
             4: ("length", "double", False), 5: ("mesh_path", "string", False), 6: ("mesh_scale", "double", True)}
_VISUAL = {1: ("name", "string", False), 2: ("origin", _POSE, False), 3: ("geometry", _GEOMETRY, False),
           4: ("rgba", "double", True)}
_LINK = {1: ("name", "string", False), 2: ("body", "int", False), 3: ("position", "double", True),
         4: ("orientation", "double", True), 5: ("visuals", _VISUAL, True)}
_JOINT = {1: ("name", "string", False), 2: ("type", "string", False), 3: ("joint", "int", False)}
MODEL = {1: ("id", "int", False), 2: ("name", "string", False), 3: ("source", "string", False),
         4: ("fixed_base", "bool", False), 6: ("links", _LINK, True), 7: ("joints", _JOINT, True)}


def _visual(v):
    g, origin = v.get("geometry", {}), v.get("origin", {})
    out = {"kind": GEOMETRY_KINDS.get(g.get("type", 0), "unknown"),
           "position": origin.get("position", [0.0] * 3), "orientation": origin.get("orientation", [1.0, 0, 0, 0]),
           "rgba": v.get("rgba", [0.7, 0.7, 0.7, 1.0])}
    if out["kind"] == "box":
        out["size"] = g.get("box_size", [0.0] * 3)
    elif out["kind"] == "mesh":
        out["mesh_path"] = g.get("mesh_path", "")
        out["scale"] = g.get("mesh_scale", [1.0] * 3)
    else:
        out["radius"] = g.get("radius", 0.0)
        out["length"] = g.get("length", 0.0)
    return out


def model_entry(m):
    """{id, name, source, fixed_base, links: [{name, body, position, orientation,
    visuals}], joints: [{name, type, joint}]} of one parsed ModelRecord."""
    links = [{"name": l.get("name", ""), "body": l.get("body", 0), "position": l.get("position", [0.0] * 3),
              "orientation": l.get("orientation", [1.0, 0, 0, 0]),
              "visuals": [_visual(v) for v in l.get("visuals", [])]} for l in m.get("links", [])]
    joints = [{"name": j.get("name", ""), "type": j.get("type", ""), "joint": j.get("joint", 0)}
              for j in m.get("joints", [])]
    return {"id": m.get("id", 0), "name": m.get("name", ""), "source": m.get("source", ""),
            "fixed_base": m.get("fixed_base", False), "links": links, "joints": joints}
