// The vertices of a mesh file (STL, OBJ, DAE, and whatever else Open Asset
// Import Library reads), for a collision geometry: the builder takes their
// convex hull, as PyBullet and MuJoCo do for a mesh by default. A visual
// mesh is kept as a path for the viewer and never read here.
//
// Every vertex of every mesh the scene's node tree instances is returned
// in the file's root frame: each node's transform is composed down the
// tree (a mesh placed twice gives its vertices twice), then `scale` (the
// model file's per-axis <mesh scale>) is applied. Units: a COLLADA file's
// <unit meter="..."> is applied by assimp's loader (a scale on the root
// node, which the node walk composes), so a DAE in centimetres comes out in
// metres; STL and OBJ carry no unit and are read as metres, as URDF and SDF
// specify. A COLLADA <up_axis> is not applied (assimp would turn Z_UP files
// to Y up): robot meshes are in their link's frame as written, as RViz (it
// keeps the root node's scale and drops its rotation), MoveIt's
// geometric_shapes and Gazebo take them.
#pragma once

#include <string>
#include <vector>

#include "service/model/read_limits.h"
#include "service/physics/math.h"
#include "service/physics/status.h"

namespace contactsim::model {

Status ReadMeshVertices(const std::string& path, const Vec3& scale, const ReadLimits& limits,
                        std::vector<Vec3>* vertices);

// The triangles of a mesh file, for a static triangle mesh (its faces as
// triangles, three indices into `vertices` each; the same node walk, scale
// and units as above, corners shared between faces once).
Status ReadMeshTriangles(const std::string& path, const Vec3& scale, const ReadLimits& limits,
                         std::vector<Vec3>* vertices, std::vector<int>* indices);

}  // namespace contactsim::model
