// The joints of a body grid's comb (scene.proto, BodyGrid.comb_joints):
// Box3D's joint grid (a lattice of spheres, each joined to its neighbours)
// without its loops. Each column (fixed i, j) is a chain up to the top
// row, and the top row (k = nz - 1) a chain along x, so the joints form a
// tree through the dynamic bodies: the linear-time tree solve of
// service/contact/joints/joint_tree_solver.h takes it, where the full
// grid's loops would send 30,000 joint rows of a 100 x 100 grid to the
// dense O(n^3) solve (joint_solver.h).
#pragma once

#include <string>

#include "service/proto/scene.pb.h"
#include "service/scene/scene_spec.h"

namespace contactsim {

// True for the top row's middle `fixed_top` bodies (the comb's anchors).
bool GridCombAnchor(const proto::BodyGrid& g, int i, int k);

// Checks comb_joints and fixed_top; InvalidArgument naming `where` and the
// field otherwise.
Status CheckGridComb(const proto::BodyGrid& g, const std::string& where);

// Appends the comb's ball joints of the grid whose bodies start at
// scene->bodies[first] (in ExpandGrid's order: i fastest, then j, then k).
void AddGridComb(const proto::BodyGrid& g, const std::string& where, size_t first, SceneSpec* scene);

}  // namespace contactsim
