// Parameters of the lcp contact method (lcp_method.h): the struct holds the
// defaults; each one's range, unit and meaning are declared once, in
// LcpParamTable() (lcp_params.cpp; param_table.h).
#pragma once

#include <string>

#include "service/contact/joint_substeps.h"
#include "service/contact/param_table.h"

namespace contactsim {

struct LcpParams {
  std::string solver = "pgs";
  int iterations = 20;
  // m/s: a warm-started resting pyramid meets 1e-4 in about three sweeps
  // and stands as it does at 1e-6 with eleven (BENCHMARKS.md, "### lcp")
  double tolerance = 1e-4;
  bool warm_start = true;
  int max_pivots = 0;
  int max_lemke_rows = 600;
  double restitution_threshold = 0.01;   // m/s
  double slop = 1e-3;                    // m
  std::string drift = "split";
  double erp = 0.2;
  double direct_mass_ratio = 10.0;
  int direct_max_rows = 300;
  double joint_substep_ratio = 100.0;
  int joint_substeps = 4;
  std::string patch_torsion = "off";     // patch_torsion.h
  std::string impacts = "sequential";    // lcp_impacts.h
};

const ParamTable<LcpParams>& LcpParamTable();

}  // namespace contactsim
