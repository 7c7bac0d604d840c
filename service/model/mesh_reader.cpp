#include "service/model/mesh_reader.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <system_error>

namespace contactsim::model {
namespace {

Status TooManyVertices(const std::string& path, size_t max_vertices) {
  return Status::ResourceExhausted("mesh '" + path + "' has more than " + std::to_string(max_vertices) +
                                   " vertices (the limit max_mesh_vertices)");
}

// Appends the vertices of `node` and its children, with `parent` the
// transform from the node's parent to the file's root frame, and, when
// `indices` is given, their triangles (three indices into `out` each; a
// point or line primitive is left out).
Status CollectVertices(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, const Vec3& scale,
                       size_t max_vertices, const std::string& path, std::vector<Vec3>* out,
                       std::vector<int>* indices = nullptr) {
  const aiMatrix4x4 to_root = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const int first = static_cast<int>(out->size());
    if (out->size() + mesh.mNumVertices > max_vertices) return TooManyVertices(path, max_vertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = to_root * mesh.mVertices[v];
      const Vec3 vertex(scale.x() * p.x, scale.y() * p.y, scale.z() * p.z);
      if (!IsFinite(vertex)) return Status::InvalidArgument("mesh '" + path + "' has a vertex that is not finite");
      out->push_back(vertex);
    }
    for (unsigned f = 0; indices != nullptr && f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned k = 0; k < 3; ++k) indices->push_back(first + static_cast<int>(face.mIndices[k]));
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    Status st = CollectVertices(scene, *node.mChildren[c], to_root, scale, max_vertices, path, out, indices);
    if (!st.ok()) return st;
  }
  return Status::Ok();
}

// The checks of the file before assimp reads it: it exists, within the size limit.
Status CheckMeshFile(const std::string& path, const Vec3& scale, const ReadLimits& limits) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec) return Status::NotFound("mesh '" + path + "' cannot be read: " + ec.message());
  if (bytes > limits.max_mesh_bytes) {
    return Status::ResourceExhausted("mesh '" + path + "' is " + std::to_string(bytes) + " bytes, over the limit of " +
                                     std::to_string(limits.max_mesh_bytes) + " (max_mesh_bytes)");
  }
  if (!scale.allFinite()) return Status::InvalidArgument("mesh '" + path + "' has a scale that is not finite");
  return Status::Ok();
}

}  // namespace

Status ReadMeshVertices(const std::string& path, const Vec3& scale, const ReadLimits& limits,
                        std::vector<Vec3>* vertices) {
  Status checked = CheckMeshFile(path, scale, limits);
  if (!checked.ok()) return checked;
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // no post-processing: the hull needs positions only, and the sort below
  // welds the corners that STL repeats in every triangle exactly, in a
  // fraction of the time assimp's JoinIdenticalVertices takes (BENCHMARKS.md,
  // "Robot models: load time")
  const aiScene* scene = importer.ReadFile(path, 0);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    return Status::InvalidArgument("mesh '" + path + "' cannot be read: " + importer.GetErrorString());
  }
  // every corner as the file repeats it (max_mesh_bytes bounds them); the
  // vertex limit counts the distinct ones
  std::vector<Vec3> out;
  Status st = CollectVertices(*scene, *scene->mRootNode, aiMatrix4x4(), scale, std::numeric_limits<size_t>::max(),
                              path, &out);
  if (!st.ok()) return st;
  if (out.empty()) return Status::InvalidArgument("mesh '" + path + "' has no vertices");
  // each corner once: STL and OBJ give a corner once per face that uses it
  std::sort(out.begin(), out.end(), [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (out.size() > limits.max_mesh_vertices) return TooManyVertices(path, limits.max_mesh_vertices);
  *vertices = std::move(out);
  return Status::Ok();
}

Status ReadMeshTriangles(const std::string& path, const Vec3& scale, const ReadLimits& limits,
                         std::vector<Vec3>* vertices, std::vector<int>* indices) {
  Status st = CheckMeshFile(path, scale, limits);
  if (!st.ok()) return st;
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // polygons as triangles; corners shared between faces once, so that
  // adjacent triangles share their edges' vertices
  const aiScene* scene = importer.ReadFile(path, aiProcess_JoinIdenticalVertices | aiProcess_Triangulate);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    return Status::InvalidArgument("mesh '" + path + "' cannot be read: " + importer.GetErrorString());
  }
  std::vector<Vec3> v;
  std::vector<int> i;
  st = CollectVertices(*scene, *scene->mRootNode, aiMatrix4x4(), scale, limits.max_mesh_vertices, path, &v, &i);
  if (!st.ok()) return st;
  if (i.empty()) return Status::InvalidArgument("mesh '" + path + "' has no triangles");
  *vertices = std::move(v);
  *indices = std::move(i);
  return Status::Ok();
}

}  // namespace contactsim::model
