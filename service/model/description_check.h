// The checks every reader runs on the description it made, so that URDF and
// SDF refuse the same things with the same words (docs/models.md, "Errors").
//
// CheckTree: link and joint names unique, every joint's parent and child a
// link of the model, no link the child of two joints, exactly one root (a
// link no joint names as child), and no kinematic loop. With one parent per
// link, a loop is exactly a set of links the root does not reach; it is
// reported as the cycle of parents ("a -> b -> c -> a"). Sets root_link.
//
// CheckValues: every number finite; a positive mass (the readers turn an
// explicit zero mass into a massless link first); an inertia that is
// symmetric positive definite and whose principal moments satisfy the
// triangle inequality I1 + I2 >= I3 for each order (a real body's moments
// do: I1 + I2 - I3 = 2 * integral of z^2 dm >= 0), within
// kInertiaTolerance of their sum, since files print rounded moments;
// collision sizes positive (visual sizes not negative); joint axes of non-zero length (normalised here)
// for joints that have one; limits with lower <= upper and non-negative
// effort and velocity; non-negative damping and friction; mimics as
// CheckMimics checks them.
//
// CheckMimics (mimic_check.cpp): a mimic names another joint of the model,
// both joints have one coordinate of the same kind (revolute or continuous
// with revolute or continuous, prismatic with prismatic), the multiplier
// and offset are finite, and no chain of mimics comes back to where it
// started.
#pragma once

#include "service/model/model_description.h"
#include "service/model/read_limits.h"
#include "service/model/source_map.h"
#include "service/physics/status.h"

namespace contactsim::model {

// Relative slack of the inertia checks, against the sum of the principal
// moments: files print moments with 4 to 6 significant digits, and a thin
// rod or disc meets the triangle inequality with equality.
inline constexpr double kInertiaTolerance = 1e-4;

Status CheckCounts(size_t links, size_t joints, const ReadLimits& limits, const SourceMap& where);
Status CheckTree(const SourceMap& where, ModelDescription* model);
Status CheckValues(const SourceMap& where, ModelDescription* model);
Status CheckMimics(const SourceMap& where, const ModelDescription& model);

// The opening of every reader: names the source ("<inline>" for text
// without a path) in `where` and refuses text over limits.max_file_bytes.
Status CheckFileSize(const std::string& text, const std::string& source_path, const ReadLimits& limits,
                     SourceMap* where);

// Whether a joint type moves along or about an axis (revolute, continuous,
// prismatic, planar's normal); fixed and floating have none.
bool HasAxis(JointType type);

}  // namespace contactsim::model
