#include "service/model/description_meshes.h"

#include <array>
#include <map>
#include <utility>

#include "service/model/mesh_reader.h"

namespace contactsim::model {

Status ResolveMeshes(const std::string& base_dir, const ModelPaths& paths, const ReadLimits& limits,
                     const SourceMap& where, ModelDescription* model) {
  size_t total = 0;
  // a file the model names twice (a left and a right finger) is read once
  std::map<std::pair<std::string, std::array<double, 3>>, const Geometry*> read;
  for (Link& link : model->links) {
    const std::string w = where.Link(link.name);
    for (size_t i = 0; i < link.collisions.size(); ++i) {
      Geometry& g = link.collisions[i].geometry;
      if (g.type != GeometryType::kMesh) continue;
      const std::string what = "collision " + std::to_string(i) + ": ";
      Status st = ResolveModelUri(g.mesh_path, base_dir, paths, &g.mesh_path);
      const auto key = std::make_pair(g.mesh_path, std::array<double, 3>{g.mesh_scale.x(), g.mesh_scale.y(),
                                                                           g.mesh_scale.z()});
      const auto same = read.find(key);
      if (st.ok() && same != read.end()) {
        g.mesh_vertices = same->second->mesh_vertices;
      } else if (st.ok()) {
        st = ReadMeshVertices(g.mesh_path, g.mesh_scale, limits, &g.mesh_vertices);
        if (st.ok()) read.emplace(key, &g);
      }
      if (!st.ok()) return st.Prefixed(w + what);
      total += g.mesh_vertices.size();
      if (total > limits.max_total_mesh_vertices) {
        return Status::ResourceExhausted(w + what + "the model's collision meshes have more than " +
                                         std::to_string(limits.max_total_mesh_vertices) +
                                         " vertices (max_total_mesh_vertices)");
      }
    }
    for (size_t i = 0; i < link.visuals.size(); ++i) {
      Geometry& g = link.visuals[i].geometry;
      if (g.type != GeometryType::kMesh) continue;
      Status st = ResolveModelUri(g.mesh_path, base_dir, paths, &g.mesh_path);
      if (!st.ok()) return st.Prefixed(w + "visual " + std::to_string(i) + ": ");
    }
  }
  return Status::Ok();
}

}  // namespace contactsim::model
