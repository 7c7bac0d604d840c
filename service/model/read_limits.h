// Bounds on what a model file may ask of the readers, so that one file
// cannot exhaust the server's memory or time. The defaults hold every file
// in PyBullet's pybullet_data with a margin (measured over the ones the
// readers take: at most 31 links, and 85,135 vertices in one collision
// mesh); docs/models.md, "Limits".
#pragma once

#include <cstddef>

namespace contactsim::model {

struct ReadLimits {
  size_t max_file_bytes = 16u << 20;        // bytes of the URDF or SDF text
  size_t max_links = 1000;
  size_t max_joints = 1000;
  size_t max_mesh_bytes = 64u << 20;        // bytes of one mesh file
  size_t max_mesh_vertices = 200000;        // distinct vertices of one mesh (as stored, for a render mesh)
  size_t max_total_mesh_vertices = 2000000; // over every collision mesh of a model
};

}  // namespace contactsim::model
