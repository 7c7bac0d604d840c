// Parameters of the impulse method (impulse_method.h): the struct holds the
// defaults; each one's range, unit and meaning are declared once, in
// ImpulseParamTable() (impulse_params.cpp; param_table.h).
#pragma once

#include <string>

#include "service/contact/joint_substeps.h"
#include "service/contact/param_table.h"

namespace contactsim {

struct ImpulseParams {
  int iterations = 30;
  int impact_sweeps = 5;  // 0: off (impulse_method.h, step 6)
  int collision_passes = 20;
  double velocity_tolerance = 1e-4;   // m/s
  double collision_threshold = 0.01;  // m/s
  double slop = 1e-3;                 // m
  double position_correction = 0.2;
  std::string toi = "regula_falsi";
  int max_substeps = 4;
  bool warm_start = true;
  double direct_mass_ratio = 10.0;
  int direct_max_rows = 300;
  double joint_substep_ratio = 100.0;
  int joint_substeps = 4;
  std::string patch_torsion = "off";  // patch_torsion.h
};

const ParamTable<ImpulseParams>& ImpulseParamTable();

}  // namespace contactsim
