#include "service/scene/grid_comb.h"

namespace contactsim {

bool GridCombAnchor(const proto::BodyGrid& g, int i, int k) {
  const int first = (g.nx() - g.fixed_top()) / 2;
  return k == g.nz() - 1 && i >= first && i < first + g.fixed_top();
}

Status CheckGridComb(const proto::BodyGrid& g, const std::string& where) {
  if (!g.comb_joints().empty() && g.comb_joints() != "ball") {
    return Status::InvalidArgument(where + ": comb_joints must be \"ball\" or empty, got \"" + g.comb_joints() + "\"");
  }
  if (!g.comb_joints().empty() && g.prototype().name().empty()) {
    return Status::InvalidArgument(where + ": comb_joints needs a named prototype (the joints name the bodies)");
  }
  if (g.fixed_top() < 0 || g.fixed_top() > g.nx()) {
    return Status::InvalidArgument(where + ": fixed_top must be between 0 and nx = " + std::to_string(g.nx()) +
                                   ", got " + std::to_string(g.fixed_top()));
  }
  return Status::Ok();
}

void AddGridComb(const proto::BodyGrid& g, const std::string& where, size_t first, SceneSpec* scene) {
  if (g.comb_joints().empty()) return;
  const auto index = [&](int i, int j, int k) { return first + (static_cast<size_t>(k) * g.ny() + j) * g.nx() + i; };
  const auto join = [&](size_t a, size_t b, const char* along) {
    const BodySettings& body_a = scene->bodies[a];
    const BodySettings& body_b = scene->bodies[b];
    if (body_a.fixed && body_b.fixed) return;
    SceneJoint joint;
    joint.settings.kind = JointKind::kBall;
    joint.settings.anchor = 0.5 * (body_a.position + body_b.position);
    joint.body_a = body_a.name;
    joint.body_b = body_b.name;
    scene->joints.push_back(std::move(joint));
    scene->joint_origins.push_back(where + ": comb joint of " + body_a.name + " " + along);
  };
  for (int j = 0; j < g.ny(); ++j) {
    for (int i = 0; i < g.nx(); ++i) {
      for (int k = 0; k + 1 < g.nz(); ++k) join(index(i, j, k), index(i, j, k + 1), "up");
    }
    for (int i = 0; i + 1 < g.nx(); ++i) join(index(i, j, g.nz() - 1), index(i + 1, j, g.nz() - 1), "along x");
  }
}

}  // namespace contactsim
