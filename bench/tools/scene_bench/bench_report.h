// A run's result as one JSON object (--json) or as a readable table.
//
// JSON fields: scene, method, threads, params, bodies, steps, dt,
// ms_per_step (median of the repeats), ms_per_step_min, ms_per_step_max,
// max_penetration, final_kinetic_energy, top_displacement and
// rebound_height (null when the scene has no body "top" / "ball", or the
// ball never rebounded), peak_rss_mb; and engine, status ("ok" or why the
// run stopped) and steps_done. Non-finite numbers are written as null.
#pragma once

#include <ostream>
#include <string>

#include "bench/tools/scene_bench/run_scene.h"

namespace contactsim::bench {

std::string ToJson(const BenchResult& result);
void PrintTable(const BenchResult& result, std::ostream& out);

}  // namespace contactsim::bench
