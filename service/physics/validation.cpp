#include "service/physics/validation.h"

#include <cmath>
#include <sstream>

namespace contactsim {

std::string FormatValue(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

std::string FormatValue(const Vec3& v) {
  return "(" + FormatValue(v.x()) + ", " + FormatValue(v.y()) + ", " + FormatValue(v.z()) + ")";
}

Status CheckFinite(const std::string& field, double v) {
  if (std::isfinite(v)) return Status::Ok();
  return Status::InvalidArgument(field + " must be a finite number, got " + FormatValue(v));
}

Status CheckFinite(const std::string& field, const Vec3& v) {
  if (v.allFinite()) return Status::Ok();
  return Status::InvalidArgument(field + " must be finite, got " + FormatValue(v));
}

Status CheckPositive(const std::string& field, double v) {
  if (std::isfinite(v) && v > 0.0) return Status::Ok();
  return Status::InvalidArgument(field + " must be a finite number > 0, got " + FormatValue(v));
}

Status CheckNonNegative(const std::string& field, double v) {
  if (std::isfinite(v) && v >= 0.0) return Status::Ok();
  return Status::InvalidArgument(field + " must be a finite number >= 0, got " + FormatValue(v));
}

Status CheckInRange(const std::string& field, double v, double lo, double hi) {
  if (std::isfinite(v) && v >= lo && v <= hi) return Status::Ok();
  return Status::InvalidArgument(field + " must be in [" + FormatValue(lo) + ", " + FormatValue(hi) + "], got " +
                                 FormatValue(v));
}

Status MakeOrientation(const std::string& field, const Eigen::Vector4d& wxyz, bool zero_is_identity, Quat* q) {
  if (!wxyz.allFinite()) {
    return Status::InvalidArgument(field + " must be finite, got (" + FormatValue(wxyz[0]) + ", " +
                                   FormatValue(wxyz[1]) + ", " + FormatValue(wxyz[2]) + ", " +
                                   FormatValue(wxyz[3]) + ")");
  }
  if (zero_is_identity && wxyz.isZero(0.0)) {
    *q = Quat::Identity();
    return Status::Ok();
  }
  const double norm = wxyz.norm();
  if (norm < 1e-9) return Status::InvalidArgument(field + " must be a unit quaternion (w, x, y, z), got norm " + FormatValue(norm));
  *q = Quat(wxyz[0] / norm, wxyz[1] / norm, wxyz[2] / norm, wxyz[3] / norm);
  return Status::Ok();
}

}  // namespace contactsim
