#include "service/model/body_plan.h"

namespace contactsim::model {
namespace {

// Adds a link's inertial, given in a frame at `at` in the body frame, to
// the running sums: mass, first moment, and the second moments about the
// body origin, from which the inertia about the combined centre is taken
// at the end (AddMass, then FinishMass).
void AddMass(const Inertial& in, const Pose& at, BodyPlan* b, Vec3* first, Mat3* second) {
  const Pose c = Compose(at, in.origin);
  const Mat3 R = c.orientation.toRotationMatrix();
  const Vec3& p = c.position;
  b->mass += in.mass;
  *first += in.mass * p;
  // inertia about the body origin: rotated own inertia plus m (|p|^2 1 - p p^T)
  *second += R * in.inertia * R.transpose() + in.mass * (p.squaredNorm() * Mat3::Identity() - p * p.transpose());
  b->has_mass = true;
}

void FinishMass(const Vec3& first, const Mat3& second, BodyPlan* b) {
  if (!b->has_mass) return;
  b->com = first / b->mass;
  const Vec3& c = b->com;
  b->inertia = second - b->mass * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
  b->inertia = 0.5 * (b->inertia + b->inertia.transpose());  // exact symmetry after the sums
}

}  // namespace

void PlanBodies(const ModelDescription& d, const ModelTree& tree, std::vector<BodyPlan>* bodies,
                std::vector<int>* link_body, std::vector<Pose>* link_in_body) {
  bodies->clear();
  link_body->assign(d.links.size(), -1);
  link_in_body->assign(d.links.size(), Pose());
  // parents come first in tree.order, so a welded child finds its parent's body
  for (int li : tree.order) {
    const int pj = tree.parent_joint[li];
    if (pj >= 0 && d.joints[pj].type == JointType::kFixed) {
      const int parent = tree.parent_link[li];
      (*link_body)[li] = (*link_body)[parent];
      (*link_in_body)[li] = Compose((*link_in_body)[parent], d.joints[pj].origin);
      (*bodies)[(*link_body)[li]].links.push_back(li);
    } else {
      (*link_body)[li] = static_cast<int>(bodies->size());
      BodyPlan b;
      b.owner = li;
      b.links.push_back(li);
      bodies->push_back(std::move(b));
    }
  }
  for (BodyPlan& b : *bodies) {
    Vec3 first = Vec3::Zero();
    Mat3 second = Mat3::Zero();
    for (int li : b.links) {
      const Link& link = d.links[li];
      const Pose& at = (*link_in_body)[li];
      if (link.inertial) AddMass(*link.inertial, at, &b, &first, &second);
      for (size_t k = 0; k < link.collisions.size(); ++k) {
        const CollisionElement& c = link.collisions[k];
        b.parts.push_back({&c.geometry, Compose(at, c.origin),
                           ModelWhere(d) + ", link \"" + link.name + "\", collision " + std::to_string(k)});
      }
    }
    FinishMass(first, second, &b);
  }
}

}  // namespace contactsim::model
