#include "service/scene/scene_spec.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <random>

#include "service/collision/aabb.h"
#include "service/collision/height_field.h"
#include "service/collision/triangle_mesh.h"
#include "service/collision/narrowphase.h"
#include "service/model/mesh_reader.h"
#include "service/physics/portable_math.h"
#include "service/physics/validation.h"
#include "service/proto/scene.pb.h"
#include "service/scene/height_map_file.h"
#include "service/scene/proto_text.h"
#include "service/scene/grid_comb.h"
#include "service/scene/terrain_grid.h"

namespace contactsim {
namespace {

using google::protobuf::TextFormat;

Vec3 ToVec3(const proto::Vector3& v) { return Vec3(v.x(), v.y(), v.z()); }

Material ToMaterial(const proto::Material& m) {
  Material out;
  out.restitution = m.restitution();
  out.friction = m.friction();
  return out;
}

Eigen::Vector4d ToWxyz(const proto::Quaternion& q) { return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()); }

// A part's shape fields; an unset shape stays kCount, which CreateBody
// refuses naming the part.
ShapePart ToShapePart(const proto::Part& p) {
  ShapePart part;
  switch (p.shape_case()) {
    case proto::Part::kSphere:
      part.type = ShapeType::kSphere;
      part.radius = p.sphere().radius();
      break;
    case proto::Part::kBox:
      part.type = ShapeType::kBox;
      part.half_extents = ToVec3(p.box().half_extents());
      break;
    case proto::Part::kCapsule:
      part.type = ShapeType::kCapsule;
      part.radius = p.capsule().radius();
      part.half_length = p.capsule().half_length();
      break;
    case proto::Part::kConvex:
      part.type = ShapeType::kConvex;
      for (const auto& v : p.convex().points()) part.points.push_back(ToVec3(v));
      break;
    case proto::Part::SHAPE_NOT_SET: part.type = ShapeType::kCount; break;
  }
  part.position = ToVec3(p.position());
  const Eigen::Vector4d q = ToWxyz(p.orientation());
  part.orientation = Quat(q[0], q[1], q[2], q[3]);
  return part;
}

// The explicit mass properties, when the file gives them.
void ToMassProperties(const proto::Body& b, BodySettings* s) {
  if (b.has_center_of_mass()) s->center_of_mass = ToVec3(b.center_of_mass());
  if (b.has_inertia()) {
    const proto::Inertia& i = b.inertia();
    Mat3 I;
    I << i.ixx(), i.ixy(), i.ixz(), i.ixy(), i.iyy(), i.iyz(), i.ixz(), i.iyz(), i.izz();
    s->inertia = I;
  }
}

// A file a scene names: a relative path is against the scene file's folder.
std::string SceneRelative(const std::string& name, const std::string& filename) {
  std::filesystem::path path(name);
  if (path.is_relative()) path = std::filesystem::path(filename).parent_path() / path;
  return path.string();
}

TerrainSpec ToTerrainSpec(const proto::Terrain& t) {
  TerrainSpec s;
  s.rows = t.rows();
  s.cols = t.cols();
  s.spacing_x = t.spacing_x();
  s.spacing_y = t.spacing_y();
  s.amplitude = t.amplitude();
  s.wavelength_x = t.wavelength_x();
  s.wavelength_y = t.wavelength_y();
  s.bowl = t.bowl();
  return s;
}

// A surface's geometry comes from one source: listed in the file, a file
// it names or a terrain.
Status CheckOneSource(const char* listed, int sources) {
  if (sources <= 1) return Status::Ok();
  return Status::InvalidArgument(std::string("a ") + listed + ", a path or a terrain, only one of them");
}

// A mesh's or heightfield's surface, built by the collision layer's
// builders (their messages name the problem); a mesh file or a height map
// is read first (SceneRelative), a terrain generated (terrain_grid.h).
Status ToSurface(const proto::Body& b, const std::string& filename, BodySettings* s) {
  if (b.has_mesh()) {
    const proto::Mesh& m = b.mesh();
    std::vector<Vec3> vertices;
    std::vector<int> indices(m.indices().begin(), m.indices().end());
    const bool listed = m.vertices_size() != 0 || m.indices_size() != 0;
    Status st = CheckOneSource("mesh gives its vertices and indices", listed + !m.path().empty() + m.has_terrain());
    if (!st.ok()) return st;
    if (m.has_terrain()) {
      const TerrainSpec t = ToTerrainSpec(m.terrain());
      std::vector<double> heights;
      st = TerrainHeights(t, &heights);
      if (!st.ok()) return st;
      GridTriangles(t.rows, t.cols, t.spacing_x, t.spacing_y, heights, &vertices, &indices);
    } else if (!m.path().empty()) {
      st = model::ReadMeshTriangles(SceneRelative(m.path(), filename), Vec3::Ones(), model::ReadLimits(), &vertices,
                                    &indices);
      if (!st.ok()) return st;
    } else {
      for (int i = 0; i + 2 < m.vertices_size(); i += 3) {
        vertices.emplace_back(m.vertices(i), m.vertices(i + 1), m.vertices(i + 2));
      }
      if (m.vertices_size() % 3 != 0) {
        return Status::InvalidArgument("mesh vertices must be x y z per vertex, got " +
                                       std::to_string(m.vertices_size()) + " values");
      }
    }
    return BuildTriangleMesh(vertices, indices, m.scale(), &s->mesh);
  }
  if (b.has_heightfield()) {
    const proto::Heightfield& h = b.heightfield();
    const int sources = (h.heights_size() != 0) + !h.path().empty() + h.has_terrain();
    Status st = CheckOneSource("heightfield gives its heights", sources);
    if (!st.ok()) return st;
    if (h.has_terrain()) {
      const TerrainSpec t = ToTerrainSpec(h.terrain());
      std::vector<double> heights;
      st = TerrainHeights(t, &heights);
      return st.ok() ? BuildHeightField(t.rows, t.cols, heights, t.spacing_x, t.spacing_y, &s->heightfield) : st;
    }
    if (h.path().empty()) {
      const std::vector<double> heights(h.heights().begin(), h.heights().end());
      return BuildHeightField(h.rows(), h.cols(), heights, h.spacing_x(), h.spacing_y(), &s->heightfield);
    }
    HeightMap map;
    st = ReadHeightMap(SceneRelative(h.path(), filename), h.rows(), h.cols(), h.scale(), h.offset(), &map);
    if (!st.ok()) return st;
    return BuildHeightField(map.rows, map.cols, map.heights, h.spacing_x(), h.spacing_y(), &s->heightfield);
  }
  return Status::Ok();
}

BodySettings ToBodySettings(const proto::Body& b, const Material& default_material) {
  BodySettings s;
  s.name = b.name();
  switch (b.shape_case()) {
    case proto::Body::kSphere:
      s.shape = ShapeType::kSphere;
      s.radius = b.sphere().radius();
      break;
    case proto::Body::kBox:
      s.shape = ShapeType::kBox;
      s.half_extents = ToVec3(b.box().half_extents());
      break;
    case proto::Body::kPlane:
      s.shape = ShapeType::kPlane;
      s.plane_normal = b.plane().has_normal() ? ToVec3(b.plane().normal()) : Vec3::UnitZ();
      s.plane_offset = b.plane().offset();
      break;
    case proto::Body::kCapsule:
      s.shape = ShapeType::kCapsule;
      s.radius = b.capsule().radius();
      s.half_length = b.capsule().half_length();
      break;
    case proto::Body::kConvex:
      s.shape = ShapeType::kConvex;
      for (const auto& p : b.convex().points()) s.points.push_back(ToVec3(p));
      break;
    case proto::Body::kCompound:
      s.shape = ShapeType::kCompound;
      for (const proto::Part& p : b.compound().parts()) s.parts.push_back(ToShapePart(p));
      break;
    case proto::Body::kMesh: s.shape = ShapeType::kMesh; break;              // ToSurface builds it
    case proto::Body::kHeightfield: s.shape = ShapeType::kHeightfield; break;
    case proto::Body::SHAPE_NOT_SET:
      s.shape = ShapeType::kCount;  // rejected by CreateBody
      break;
  }
  s.position = ToVec3(b.position());
  if (b.has_orientation()) {
    const auto& q = b.orientation();
    s.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
  }
  s.linear_velocity = ToVec3(b.linear_velocity());
  s.angular_velocity = ToVec3(b.angular_velocity());
  if (b.has_mass()) s.mass = b.mass();
  if (b.has_density()) s.density = b.density();
  s.fixed = b.fixed();
  s.kinematic = b.kinematic();
  ToMassProperties(b, &s);
  const Material m = b.has_material() ? ToMaterial(b.material()) : default_material;
  s.restitution = m.restitution;
  s.friction = m.friction;
  s.collision_category = b.filter().category();
  s.collision_mask = b.filter().mask();
  s.collision_group = b.filter().group();
  return s;
}

// Uniform in [0, 1) from 53 random bits: the same on every platform, unlike
// std::uniform_real_distribution.
double Uniform01(std::mt19937_64& rng) { return (rng() >> 11) * (1.0 / 9007199254740992.0); }

// Uniformly random rotation (Shoemake 1992, "Uniform random rotations").
Eigen::Vector4d RandomOrientation(std::mt19937_64& rng) {
  const double u1 = Uniform01(rng), u2 = Uniform01(rng), u3 = Uniform01(rng);
  const double two_pi = 6.283185307179586;
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  return Eigen::Vector4d(b * portable::Cos(two_pi * u3), a * portable::Sin(two_pi * u2),
                         a * portable::Cos(two_pi * u2), b * portable::Sin(two_pi * u3));
}

Status ToSceneJoint(const proto::Joint& j, const std::string& where, SceneJoint* out) {
  SceneJoint sj;
  if (!ParseJointKind(j.kind(), &sj.settings.kind)) {
    return Status::InvalidArgument(where + ": kind must be one of distance, ball, hinge, fixed, prismatic, got \"" + j.kind() +
                                   "\"");
  }
  if (j.body_a().empty()) return Status::InvalidArgument(where + ": body_a must name a body");
  sj.body_a = j.body_a();
  sj.body_b = j.body_b();
  sj.settings.anchor = ToVec3(j.anchor());
  if (j.has_axis()) sj.settings.axis = ToVec3(j.axis());
  if (j.has_length()) sj.settings.length = j.length();
  if (j.has_limits()) {
    if (!j.limits().has_lower() || !j.limits().has_upper()) {
      return Status::InvalidArgument(where + ": limits need both lower and upper");
    }
    sj.settings.limits = std::make_pair(j.limits().lower(), j.limits().upper());
  }
  sj.settings.damping = j.damping();
  sj.settings.friction = j.friction();
  sj.settings.collide_connected = j.collide_connected();
  *out = std::move(sj);
  return Status::Ok();
}

// Random orientations redrawn until a grid body overlaps none of the grid's
// bodies placed before it: a lattice tighter than the bodies' diameter (the
// issue's box_rain: 0.3 m spacing, 0.173 m half-diagonals) would otherwise
// start with interpenetrating pairs, which every contact method then pushes
// apart violently, and which no barrier method can start from.
class GridOverlapCheck {
 public:
  GridOverlapCheck(const proto::BodyGrid& g, const BodySettings& prototype, const Material& default_material)
      : nx_(g.nx()), ny_(g.ny()), material_(default_material) {
    RigidBody body;
    BodySettings centred = prototype;
    centred.position = Vec3::Zero();
    valid_ = CreateBody(centred, default_material, &body).ok() && body.shape.type != ShapeType::kPlane;
    if (!valid_) return;  // BuildWorld reports the prototype's error
    // a sphere about the origin that holds the body in any orientation
    const Aabb box = ComputeAabb(body, 0.0, 0.0);
    const double reach = 2.0 * (0.5 * (box.max + box.min).norm() + 0.5 * (box.max - box.min).norm());
    const Vec3 spacing = ToVec3(g.spacing()).cwiseAbs();
    for (int a = 0; a < 3; ++a) {
      const int n = a == 0 ? g.nx() : a == 1 ? g.ny() : g.nz();
      cells_[a] = spacing(a) > 0.0 ? std::min(n, static_cast<int>(std::ceil(reach / spacing(a)))) : n;
    }
    placed_.resize(static_cast<size_t>(g.nx()) * g.ny() * g.nz());
  }

  // True when `s` at lattice cell (i, j, k) is clear of every body placed at
  // an earlier cell within reach (separation > 0).
  bool Clear(const BodySettings& s, int i, int j, int k) const {
    if (!valid_) return true;
    RigidBody body;
    if (!CreateBody(s, material_, &body).ok()) return true;
    const Aabb box = ComputeAabb(body, 0.0, 0.0);
    for (int kk = std::max(0, k - cells_[2]); kk <= k; ++kk) {
      for (int jj = std::max(0, j - cells_[1]); jj < std::min(ny_, j + cells_[1] + 1); ++jj) {
        for (int ii = std::max(0, i - cells_[0]); ii < std::min(nx_, i + cells_[0] + 1); ++ii) {
          const size_t at = Index(ii, jj, kk);
          if (at >= Index(i, j, k)) continue;  // not placed yet
          const RigidBody& other = placed_[at];
          if (!box.Overlaps(ComputeAabb(other, 0.0, 0.0))) continue;
          if (PairSignedDistance(body, other, 1.0) <= 0.0) return false;
        }
      }
    }
    return true;
  }

  void Place(const BodySettings& s, int i, int j, int k) {
    if (valid_) CreateBody(s, material_, &placed_[Index(i, j, k)]);
  }

 private:
  size_t Index(int i, int j, int k) const { return (static_cast<size_t>(k) * ny_ + j) * nx_ + i; }

  int nx_, ny_;
  Material material_;
  bool valid_ = false;
  int cells_[3] = {0, 0, 0};  // lattice cells within two bounding radii, per axis
  std::vector<RigidBody> placed_;
};

constexpr int kMaxOrientationDraws = 1000;

Status ExpandGrid(const proto::BodyGrid& g, const std::string& where, const Material& default_material,
                  SceneSpec* scene) {
  if (g.nx() < 1 || g.ny() < 1 || g.nz() < 1 || int64_t{g.nx()} * g.ny() * g.nz() > 1000000) {
    return Status::InvalidArgument(where + ": grids nx, ny, nz must be >= 1 with at most 1,000,000 bodies, got " +
                                   std::to_string(g.nx()) + " x " + std::to_string(g.ny()) + " x " +
                                   std::to_string(g.nz()));
  }
  Status st;
  if (!(st = CheckNonNegative("jitter", g.jitter())).ok()) return Status::InvalidArgument(where + ": grids " + st.message());
  if (!(st = CheckGridComb(g, where)).ok()) return st;
  const size_t first = scene->bodies.size();
  std::mt19937_64 rng(g.seed());
  const BodySettings proto_body = ToBodySettings(g.prototype(), default_material);
  const Vec3 origin = ToVec3(g.origin()), spacing = ToVec3(g.spacing());
  std::optional<GridOverlapCheck> overlap;
  if (g.random_orientation()) overlap.emplace(g, proto_body, default_material);
  for (int k = 0; k < g.nz(); ++k) {
    for (int j = 0; j < g.ny(); ++j) {
      for (int i = 0; i < g.nx(); ++i) {
        BodySettings s = proto_body;
        s.position = origin + Vec3(i, j, k).cwiseProduct(spacing) + s.position;
        s.position.x() += g.jitter() * (2.0 * Uniform01(rng) - 1.0);
        s.position.y() += g.jitter() * (2.0 * Uniform01(rng) - 1.0);
        if (overlap) {
          int draws = 0;
          do {
            if (++draws > kMaxOrientationDraws) {
              return Status::InvalidArgument(where + ": grids body (" + std::to_string(i) + ", " + std::to_string(j) +
                                             ", " + std::to_string(k) + ") overlaps a neighbour in each of " +
                                             std::to_string(kMaxOrientationDraws) +
                                             " random orientations; make the spacing larger");
            }
            s.orientation = RandomOrientation(rng);
          } while (!overlap->Clear(s, i, j, k));
          overlap->Place(s, i, j, k);
        }
        if (!s.name.empty()) s.name += "_" + std::to_string(scene->bodies.size());
        s.fixed = s.fixed || GridCombAnchor(g, i, k);
        scene->bodies.push_back(std::move(s));
        scene->origins.push_back(where);
      }
    }
  }
  AddGridComb(g, where, first, scene);
  return Status::Ok();
}

Status Convert(const proto::Scene& p, const std::string& filename, const TextFormat::ParseInfoTree* tree,
               SceneSpec* out) {
  SceneSpec scene;
  if (p.has_gravity()) scene.gravity = ToVec3(p.gravity());
  if (p.has_dt()) scene.dt = p.dt();
  Status st;
  if (!(st = CheckFinite("gravity", scene.gravity)).ok()) {
    return Status::InvalidArgument(FieldLocation(filename, tree, p, "gravity") + ": " + st.message());
  }
  if (!(st = CheckInRange("dt", scene.dt, 1e-6, 0.1)).ok()) {
    return Status::InvalidArgument(FieldLocation(filename, tree, p, "dt") + ": " + st.message());
  }
  if (p.has_default_material()) {
    scene.default_material = ToMaterial(p.default_material());
    if (!(st = CheckMaterial(scene.default_material.restitution, scene.default_material.friction)).ok()) {
      return Status::InvalidArgument(FieldLocation(filename, tree, p, "default_material") + ": default_material " +
                                     st.message());
    }
  }
  for (int i = 0; i < p.bodies_size(); ++i) {
    scene.bodies.push_back(ToBodySettings(p.bodies(i), scene.default_material));
    std::string where = FieldLocation(filename, tree, p, "bodies", i) + ": bodies[" + std::to_string(i) + "]";
    if (!p.bodies(i).name().empty()) where += " \"" + p.bodies(i).name() + "\"";
    if (!(st = ToSurface(p.bodies(i), filename, &scene.bodies.back())).ok()) {
      return st.Prefixed(where + ": ");
    }
    scene.origins.push_back(where);
  }
  for (int i = 0; i < p.grids_size(); ++i) {
    const std::string where = FieldLocation(filename, tree, p, "grids", i) + ": grids[" + std::to_string(i) + "]";
    if (!(st = ExpandGrid(p.grids(i), where, scene.default_material, &scene)).ok()) return st;
  }
  if (p.steps() < 0) {
    return Status::InvalidArgument(FieldLocation(filename, tree, p, "steps") + ": steps must be >= 0, got " +
                                   std::to_string(p.steps()));
  }
  scene.steps = p.steps();
  for (int i = 0; i < p.joints_size(); ++i) {
    const std::string where = FieldLocation(filename, tree, p, "joints", i) + ": joints[" + std::to_string(i) + "]";
    SceneJoint joint;
    if (!(st = ToSceneJoint(p.joints(i), where, &joint)).ok()) return st;
    scene.joints.push_back(std::move(joint));
    scene.joint_origins.push_back(where);
  }
  if (!(st = ReadSceneModels(p, filename, tree, &scene.models)).ok()) return st;
  scene.contact_method = p.contact_method();
  for (const auto& param : p.method_params()) scene.method_params[param.name()] = param.value();
  *out = std::move(scene);
  return Status::Ok();
}

}  // namespace

Status ParseSceneText(const std::string& text, const std::string& filename, SceneSpec* scene) {
  proto::Scene p;
  TextFormat::ParseInfoTree tree;
  Status st = ParseTextProto(text, filename, &p, &tree);
  if (!st.ok()) return st;
  return Convert(p, filename, &tree, scene);
}

Status LoadSceneFile(const std::string& path, SceneSpec* scene) {
  proto::Scene p;
  TextFormat::ParseInfoTree tree;
  Status st = ReadTextProto(path, &p, &tree);
  if (!st.ok()) return st;
  return Convert(p, path, &tree, scene);
}

namespace {

// The id of the one body called `name`.
Status ResolveBodyName(const std::multimap<std::string, BodyId>& names, const std::string& field,
                       const std::string& name, BodyId* id) {
  const auto count = names.count(name);
  if (count == 1) {
    *id = names.find(name)->second;
    return Status::Ok();
  }
  return Status::InvalidArgument(field + " \"" + name + "\" must name exactly one body, " +
                                 (count == 0 ? std::string("no body has this name")
                                             : std::to_string(count) + " bodies have it"));
}

}  // namespace

Status BuildWorld(const SceneSpec& scene, World* world) {
  World next;
  next.gravity = scene.gravity;
  next.dt = scene.dt;
  std::multimap<std::string, BodyId> names;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    RigidBody body;
    Status st = CreateBody(scene.bodies[i], scene.default_material, &body);
    if (!st.ok()) return Status::InvalidArgument(scene.origins[i] + ": " + st.message());
    const BodyId id = next.AddBody(std::move(body));
    if (!scene.bodies[i].name.empty()) names.emplace(scene.bodies[i].name, id);
  }
  for (size_t i = 0; i < scene.joints.size(); ++i) {
    const SceneJoint& j = scene.joints[i];
    JointSettings s = j.settings;
    Status st = ResolveBodyName(names, "body_a", j.body_a, &s.body_a);
    if (st.ok() && !j.body_b.empty()) st = ResolveBodyName(names, "body_b", j.body_b, &s.body_b);
    JointId id = 0;
    if (st.ok()) st = next.AddJoint(s, &id);
    if (!st.ok()) return Status::InvalidArgument(scene.joint_origins[i] + ": " + st.message());
  }
  if (Status st = AddSceneModels(scene.models, scene.default_material, &next); !st.ok()) return st;
  *world = std::move(next);
  return Status::Ok();
}

}  // namespace contactsim
