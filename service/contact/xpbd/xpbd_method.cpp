#include "service/contact/xpbd/xpbd_method.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "service/contact/detect_ahead.h"
#include "service/contact/joints/joint_solver.h"
#include "service/contact/soft/soft_joints.h"
#include "service/contact/xpbd/xpbd_velocity_pass.h"
#include "service/physics/byte_stream.h"
#include "service/physics/integrator.h"

namespace contactsim {

Status XpbdMethod::SetParams(const ParamMap& params) {
  return XpbdParamTable().Parse(Name(), params, params_, &params_);
}

int XpbdMethod::SubstepsFor(const World& world) const {
  // one sweep a sub-step leaves a heavy body on a light one about
  // (m_heavy / m_light) g h^2 deep (the light body takes the push): h is
  // chosen so that this stays within kMassRatioOverlap
  const auto& bodies = world.bodies();
  double ratio = 1.0;
  for (const Contact& c : contacts_) {
    const RigidBody& A = bodies[c.a];
    const RigidBody& B = bodies[c.b];
    if (!A.IsDynamic() || !B.IsDynamic()) continue;
    ratio = std::max(ratio, std::max(A.mass, B.mass) / std::min(A.mass, B.mass));
  }
  const double needed = world.dt * std::sqrt(ratio * world.gravity.norm() / kMassRatioOverlap);
  return std::max(params_.substeps, static_cast<int>(std::min(std::ceil(needed), 1000.0)));
}

void XpbdMethod::ReportContacts(const World& world, ContactSet* contacts_out, StepStats* stats) const {
  // a point is reported while it touches or carried load in the step
  const double dt = world.dt;
  for (size_t k = 0; k < contacts_.size(); ++k) {
    const XpbdPoint& p = points_[point_of_[k]];
    Vec3 pa, pb;
    const double depth = -XpbdSeparation(p, world, &pa, &pb);
    if (depth <= 0.0 && p.impulse.isZero(0.0)) continue;
    Contact c = contacts_[k];
    c.depth = depth;
    c.point = 0.5 * (pa + pb);
    c.normal_value = p.n.dot(p.impulse) / dt;
    c.tangent_value = (p.impulse - p.n * p.n.dot(p.impulse)) / dt;
    contacts_out->push_back(c);
    stats->max_penetration = std::max(stats->max_penetration, depth);
  }
}

// The slips of patches 0 of their pairs in the layout from before compound
// bodies (count, then a, b, along, twist each), then, when a pair had more
// patches or pairs are in contact, the others (count, then a, b, place,
// along, twist each), then, when pairs are in contact, their allowed
// overlaps (count, then a, b, overlap each), so a world without compounds
// or contacts saves the same bytes as before either.
std::string XpbdMethod::SaveState() const {
  if (slips_.empty() && allowed_.empty()) return {};
  ByteWriter out;
  uint64_t first = 0;
  for (const auto& entry : slips_) first += std::get<2>(entry.first) == 0;
  out.Put(first);
  for (const auto& [key, slip] : slips_) {
    if (std::get<2>(key) != 0) continue;
    out.Put(std::get<0>(key));
    out.Put(std::get<1>(key));
    out.PutVec3(slip.along);
    out.Put(slip.twist);
  }
  if (first == slips_.size() && allowed_.empty()) return out.bytes();
  out.Put(static_cast<uint64_t>(slips_.size() - first));
  for (const auto& [key, slip] : slips_) {
    if (std::get<2>(key) == 0) continue;
    out.Put(std::get<0>(key));
    out.Put(std::get<1>(key));
    out.Put(std::get<2>(key));
    out.PutVec3(slip.along);
    out.Put(slip.twist);
  }
  if (allowed_.empty()) return out.bytes();
  out.Put(static_cast<uint64_t>(allowed_.size()));
  for (const AllowedOverlap& e : allowed_) {
    out.Put(e.a);
    out.Put(e.b);
    out.Put(e.overlap);
  }
  return out.bytes();
}

Status XpbdMethod::LoadState(const std::string& bytes) {
  std::map<PairKey, XpbdPatchSlip> loaded;
  std::vector<AllowedOverlap> allowed;
  ByteReader in(bytes);
  bool ok = true;
  for (int section = 0; ok && section < 3 && !bytes.empty() && !in.done(); ++section) {
    uint64_t n = 0;
    ok = in.Get(&n);
    for (uint64_t i = 0; ok && i < n; ++i) {
      BodyId a = 0, b = 0;
      ok = in.Get(&a) && in.Get(&b);
      if (ok && section == 2) {
        double overlap = 0.0;
        ok = in.Get(&overlap) && std::isfinite(overlap) && overlap >= 0.0;
        if (ok) allowed.push_back({a, b, overlap});
        continue;
      }
      int64_t place = 0;
      XpbdPatchSlip slip;
      ok = ok && (section == 0 || (in.Get(&place) && place > 0)) && in.GetVec3(&slip.along) &&
           in.Get(&slip.twist) && slip.along.allFinite() && std::isfinite(slip.twist);
      if (ok) loaded[{a, b, place}] = slip;
    }
  }
  if (!ok || !in.done()) {
    return Status::InvalidArgument("xpbd method state: malformed friction slips or overlaps (" +
                                   std::to_string(bytes.size()) + " bytes)");
  }
  slips_ = std::move(loaded);
  SortAllowed(&allowed);
  allowed_ = std::move(allowed);
  return Status::Ok();
}

std::vector<XpbdMethod::PairKey> XpbdMethod::PatchKeys(const World& world) const {
  const auto& bodies = world.bodies();
  std::vector<int> contact_of(point_of_.size());
  for (size_t k = 0; k < point_of_.size(); ++k) contact_of[point_of_[k]] = static_cast<int>(k);
  std::vector<PairKey> keys(patches_.size());
  for (size_t k = 0; k < patches_.size(); ++k) {
    const XpbdPatch& patch = patches_[k];
    const XpbdPoint& p0 = points_[patch.first];
    const RigidBody& A = bodies[p0.a];
    const RigidBody& B = bodies[p0.b];
    int64_t place = 0;
    if (A.shape.IsCompound() || B.shape.IsCompound()) {
      // A compound's child pairs each bring a patch, and the blocks are
      // ordered by height (sweep_order.h), so a patch's place among its
      // pair's changes whenever the legs of a level table swap heights by
      // round-off: each leg's slip was then carried to another leg, a
      // turn about the vertical that the legs' friction held, and a
      // resting table spun up to 1.17 rad/s in 2 s. The patch is known by
      // its points' smallest feature id instead (which hashes the child
      // pair's indices, narrowphase.cpp), 1 + id so that 0 stays the
      // place of a plain pair's one patch.
      uint32_t id = UINT32_MAX;
      for (int i = 0; i < patch.count; ++i) id = std::min(id, contacts_[contact_of[patch.first + i]].feature_id);
      place = 1 + static_cast<int64_t>(id);
    } else if (k > 0 && std::get<0>(keys[k - 1]) == A.id && std::get<1>(keys[k - 1]) == B.id) {
      // a plain pair's patches are consecutive (its contacts are)
      place = std::get<2>(keys[k - 1]) + 1;
    }
    keys[k] = {A.id, B.id, place};
  }
  return keys;
}

void XpbdMethod::CarrySlips(const World& world) {
  if (slips_.empty()) return;
  const std::vector<PairKey> keys = PatchKeys(world);
  for (size_t k = 0; k < patches_.size(); ++k) {
    if (!patches_[k].valid) continue;
    const auto it = slips_.find(keys[k]);
    if (it != slips_.end()) CarryXpbdPatchSlip(it->second, &patches_[k]);
  }
}

void XpbdMethod::KeepSlips(const World& world) {
  slips_.clear();
  const std::vector<PairKey> keys = PatchKeys(world);
  XpbdPatchSlip slip;
  for (size_t k = 0; k < patches_.size(); ++k) {
    if (!XpbdPatchSlipNow(world, patches_[k], points_, &slip)) continue;
    slips_[keys[k]] = slip;
  }
}

void XpbdMethod::AllowStartOverlaps(const World& world, int substeps) {
  const auto& bodies = world.bodies();
  std::vector<double> most(contacts_.size());
  for (size_t k = 0; k < contacts_.size(); ++k) {
    const AllowedOverlap key{bodies[contacts_[k].a].id, bodies[contacts_[k].b].id, 0.0};
    // a pair's contacts are consecutive: one search a pair
    if (k > 0 && contacts_[k].a == contacts_[k - 1].a && contacts_[k].b == contacts_[k - 1].b) {
      most[k] = most[k - 1];
      continue;
    }
    const auto it = std::lower_bound(allowed_.begin(), allowed_.end(), key);
    const bool known = it != allowed_.end() && it->a == key.a && it->b == key.b;
    most[k] = known ? it->overlap : std::numeric_limits<double>::infinity();
  }
  AllowXpbdStartOverlaps(contacts_, point_of_, most, params_.start_overlap_velocity, params_.start_overlap_time,
                         world.dt / substeps, &points_);
}

void XpbdMethod::KeepAllowedOverlaps(const World& world) {
  const auto& bodies = world.bodies();
  kept_.clear();
  for (size_t k = 0; k < contacts_.size(); ++k) {
    const AllowedOverlap entry{bodies[contacts_[k].a].id, bodies[contacts_[k].b].id,
                               XpbdSlack(points_[point_of_[k]], world.dt)};
    if (!kept_.empty() && kept_.back().a == entry.a && kept_.back().b == entry.b) {
      kept_.back().overlap = std::max(kept_.back().overlap, entry.overlap);
    } else {
      kept_.push_back(entry);
    }
  }
  SortAllowed(&kept_);
  allowed_.swap(kept_);
}

void XpbdMethod::SortAllowed(std::vector<AllowedOverlap>* allowed) {
  std::sort(allowed->begin(), allowed->end());
  size_t out = 0;
  for (size_t i = 0; i < allowed->size(); ++i) {
    const AllowedOverlap& e = (*allowed)[i];
    if (out > 0 && (*allowed)[out - 1].a == e.a && (*allowed)[out - 1].b == e.b) {
      (*allowed)[out - 1].overlap = std::max((*allowed)[out - 1].overlap, e.overlap);
    } else {
      (*allowed)[out++] = e;
    }
  }
  allowed->resize(out);
}

StepStats XpbdMethod::Step(World& world, CollisionDetector& detector, ContactSet* contacts_out) {
  StepStats stats;
  contacts_out->clear();
  world.AccumulateForces();
  DetectAhead(world, detector, params_.margin, world.dt, &contacts_);
  auto& bodies = world.bodies();
  substepped_.assign(bodies.size(), 0);
  for (const Contact& c : contacts_) substepped_[c.a] = substepped_[c.b] = 1;
  SoftJoints::MarkJointed(world, &substepped_);
  LoadSoftBodies(world, substepped_, detector.runner(), &bodies_);
  touching_.assign(bodies.size(), 0);
  for (const Contact& c : contacts_) touching_[c.a] = touching_[c.b] = 1;
  articulation_.Prepare(world, bodies_, touching_, params_.joint_compliance == 0.0);
  PrepareXpbdPoints(contacts_, world, bodies_, articulation_, &points_, &frames_, &blocks_, &colours_, &point_of_);
  PrepareXpbdPatches(blocks_, points_, frames_, bodies_, articulation_, ParsePatchTorsion(params_.patch_torsion),
                     &patches_);
  for (XpbdPatch& patch : patches_) {
    const XpbdPoint& p0 = points_[patch.first];
    patch.compound = bodies[p0.a].shape.IsCompound() || bodies[p0.b].shape.IsCompound();
  }
  jointed_blocks_.clear();
  for (size_t k = 0; k < blocks_.size(); ++k) {
    if (points_[blocks_[k].first].jointed) jointed_blocks_.push_back(static_cast<int>(k));
  }
  CarrySlips(world);
  subsets_.assign(blocks_.size(), XpbdSubsetCache{});
  ratio_.Prepare(params_.direct_mass_ratio, bodies_, points_);
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (!bodies_[i].substepped) AdvanceBallistic(bodies[i], world.dt);
  }
  // rigid joints are met exactly after every sub-step's sweeps (xpbd_method.h, 2b)
  const bool project_joints = params_.joint_compliance == 0.0 && !world.joints().empty();
  const int substeps = SubstepsFor(world);
  AllowStartOverlaps(world, substeps);
  RunSubsteps(world, substeps, project_joints, detector.runner());
  KeepSlips(world);
  KeepAllowedOverlaps(world);
  StoreSoftBodies(bodies_, detector.runner(), world);
  ReportContacts(world, contacts_out, &stats);
  world.FinishStep();
  stats.iterations = substeps * params_.iterations;
  stats.substeps = substeps;
  stats.contacts = static_cast<int>(contacts_out->size());
  return stats;
}

}  // namespace contactsim
