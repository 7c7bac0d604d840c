// Parameters of the xpbd method (xpbd_method.h): the struct holds the
// defaults; each one's range, unit and meaning are declared once, in
// XpbdParamTable() (xpbd_params.cpp; param_table.h).
#pragma once

#include <string>

#include "service/contact/param_table.h"

namespace contactsim {

struct XpbdParams {
  int substeps = 10;
  int iterations = 1;
  double compliance = 0.0;             // m/N
  double restitution_threshold = 0.0;  // m/s
  double margin = 0.01;                // m
  double joint_compliance = 0.0;       // m/N (and rad/(N m))
  double direct_mass_ratio = 10.0;
  double max_push_velocity = 4.0;      // m/s
  int velocity_iterations = 1;
  double start_overlap_velocity = 0.002;  // m/s
  double start_overlap_time = 0.25;       // s
  std::string patch_torsion = "off";   // patch_torsion.h
};

const ParamTable<XpbdParams>& XpbdParamTable();

}  // namespace contactsim
