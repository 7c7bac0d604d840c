// Which links become which bodies, and each body's combined mass properties
// and shapes, before anything about the world is decided. A link held by a
// fixed joint joins its parent's body (recursively), so one body carries a
// link and every link welded to it; the body's frame is its owning link's
// frame (the one nearest the root).
//
// Mass properties of a merged body, in the owner link's frame (the parallel
// axis theorem; e.g. Featherstone, "Rigid Body Dynamics Algorithms", 2008,
// sec. 2.13): m = sum m_i, c = sum m_i c_i / m,
//   I_c = sum ( R_i I_i R_i^T + m_i (|d_i|^2 1 - d_i d_i^T) ),  d_i = c_i - c.
#pragma once

#include <string>
#include <vector>

#include "service/model/model_check.h"
#include "service/model/model_description.h"
#include "service/model/model_kinematics.h"

namespace contactsim::model {

struct PartPlan {
  const Geometry* geometry = nullptr;  // points into the description
  Pose origin;                         // the geometry frame in the body's (owner link's) frame
  std::string where;                   // "model ..., link ..., collision i" for errors
};

struct BodyPlan {
  int owner = -1;                      // the owning link
  std::vector<int> links;              // the owner first, then the links merged into it
  std::vector<PartPlan> parts;
  bool has_mass = false;               // some link of the body has an <inertial>
  double mass = 0.0;                   // kg
  Vec3 com = Vec3::Zero();             // m, in the owner link's frame
  Mat3 inertia = Mat3::Zero();         // kg m^2, about com, in the owner link's axes
};

// PyBullet's mass for a link without <inertial> (its URDF importer's
// default, with a warning there): 1 kg and a unit diagonal inertia at the
// link origin. Used for a body none of whose links has mass, unless it is
// the fixed base.
constexpr double kDefaultLinkMass = 1.0;             // kg
constexpr double kDefaultLinkInertia = 1.0;          // kg m^2, each principal moment

// Groups the links into bodies. link_body[i] is link i's body (index into
// *bodies), link_in_body[i] its frame in that body's owner link frame.
void PlanBodies(const ModelDescription& d, const ModelTree& tree, std::vector<BodyPlan>* bodies,
                std::vector<int>* link_body, std::vector<Pose>* link_in_body);

}  // namespace contactsim::model
