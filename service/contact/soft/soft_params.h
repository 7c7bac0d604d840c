// Parameters of the soft-step method (soft_method.h): the struct holds the
// defaults; each one's range, unit and meaning are declared once, in
// SoftParamTable() (soft_params.cpp; param_table.h).
#pragma once

#include <string>

#include "service/contact/param_table.h"

namespace contactsim {

struct SoftParams {
  int substeps = 4;                     // Box2D v3 and Box3D's default
  int relax_iterations = 1;             // per sub-step, after the positions move
  int joint_passes = 8;                 // contact pass and joint solve in turn, per solve and relax
  double contact_hertz = 120.0;          // Hz, capped at a quarter of the sub-step rate
  double damping_ratio = 10.0;          // contact springs are heavily over-damped
  double max_push_velocity = 3.0;       // m/s, fastest a soft contact pushes bodies apart
  double restitution_threshold = 0.001;  // m/s, raised to 2 |g| dt under gravity
  double margin = 0.01;                 // m, speculative distance beyond each pair's closing motion
  bool warm_start = true;
  double direct_mass_ratio = 10.0;      // soft_ratio_solve.h
  int direct_max_rows = 300;
  std::string patch_torsion = "off";   // patch_torsion.h
  std::string precision = "double";    // float: the SIMD path (wide/soft_wide_solver.h)
  std::string float_lanes = "widest";  // its bundle width: widest, 4 or 8
};

const ParamTable<SoftParams>& SoftParamTable();

}  // namespace contactsim
