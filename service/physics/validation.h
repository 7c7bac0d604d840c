// Checks for values that arrive from outside (commands, scene files). Each
// returns a status whose message names the field and the value, e.g.
// "radius must be a finite number > 0, got -1".
#pragma once

#include <string>

#include "service/physics/math.h"
#include "service/physics/status.h"

namespace contactsim {

// Largest length, position or speed a command may carry; beyond it double
// precision and the broadphase stop being meaningful.
constexpr double kMaxLength = 1e6;  // m (m/s for speeds)

std::string FormatValue(double v);
std::string FormatValue(const Vec3& v);

Status CheckFinite(const std::string& field, double v);
Status CheckFinite(const std::string& field, const Vec3& v);
Status CheckPositive(const std::string& field, double v);  // finite and > 0
Status CheckNonNegative(const std::string& field, double v);
Status CheckInRange(const std::string& field, double v, double lo, double hi);

// (w, x, y, z) -> unit quaternion. Rejects non-finite values and norms
// below 1e-9, except that all zeros means the identity where
// zero_is_identity (a new body whose orientation was left unset); setting a
// pose to the zero quaternion is an error.
Status MakeOrientation(const std::string& field, const Eigen::Vector4d& wxyz, bool zero_is_identity, Quat* q);

}  // namespace contactsim
