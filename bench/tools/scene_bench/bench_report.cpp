#include "bench/tools/scene_bench/bench_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "tools/json_text.h"

namespace contactsim::bench {
namespace {

using tools::JsonQuote;

// 9 significant digits: far below timing noise; dt is written exactly.
std::string Number(double v, int digits = 9) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string Number(const std::optional<double>& v) { return v ? Number(*v) : "null"; }

std::string Text(const std::optional<double>& v, const char* unit) {
  if (!v) return "-";
  return Number(*v) + " " + unit;
}

}  // namespace

std::string ToJson(const BenchResult& r) {
  std::ostringstream o;
  o << "{\"engine\": " << JsonQuote(r.engine) << ", \"scene\": " << JsonQuote(r.scene)
    << ", \"method\": " << JsonQuote(r.method)
    << ", \"threads\": " << r.threads << ", \"sleep\": " << (r.sleep ? "true" : "false")
    << ", \"sleeping\": " << r.sleeping << ", \"manifold_reuse\": " << (r.manifold_reuse ? "true" : "false")
    << ", \"params\": {";
  bool first = true;
  for (const auto& [key, value] : r.params) {
    o << (first ? "" : ", ") << JsonQuote(key) << ": " << JsonQuote(value);
    first = false;
  }
  o << "}, \"bodies\": " << r.bodies << ", \"steps\": " << r.steps << ", \"steps_done\": " << r.steps_done
    << ", \"dt\": " << Number(r.dt, 17) << ", \"ms_per_step\": " << Number(r.ms_per_step)
    << ", \"ms_per_step_min\": " << Number(r.ms_per_step_min) << ", \"ms_per_step_max\": " << Number(r.ms_per_step_max)
    << ", \"max_penetration\": " << Number(r.max_penetration) << ", \"min_distance\": " << Number(r.min_distance)
    << ", \"fell_through\": " << (r.fell_through ? std::to_string(*r.fell_through) : "null")
    << ", \"final_kinetic_energy\": " << Number(r.final_kinetic_energy)
    << ", \"top_displacement\": " << Number(r.top_displacement) << ", \"rebound_height\": " << Number(r.rebound_height)
    << ", \"iterations_mean\": " << Number(r.iterations_mean) << ", \"iterations_max\": " << Number(r.iterations_max)
    << ", \"residual_min\": " << Number(r.residual_min) << ", \"stiffness_max\": " << Number(r.stiffness_max)
    << ", \"peak_rss_mb\": " << Number(r.peak_rss_mb) << ", \"status\": " << JsonQuote(r.status) << "}";
  return o.str();
}

void PrintTable(const BenchResult& r, std::ostream& out) {
  std::string params;
  for (const auto& [key, value] : r.params) params += (params.empty() ? "" : " ") + key + "=" + value;
  const auto row = [&out](const char* name, const std::string& value) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "  %-22s", name);
    out << buf << value << "\n";
  };
  row("engine", r.engine);
  row("scene", r.scene + " (" + std::to_string(r.bodies) + " bodies, dt " + Number(r.dt) + " s)");
  row("method", r.method);
  row("params", params.empty() ? "-" : params);
  row("threads", std::to_string(r.threads));
  row("sleep", r.sleep ? "on (" + std::to_string(r.sleeping) + " bodies asleep at the end)" : "off");
  row("manifold reuse", r.manifold_reuse ? "on" : "off");
  row("steps", std::to_string(r.steps_done) + " of " + std::to_string(r.steps));
  row("ms per step", Number(r.ms_per_step) + " (median of " + std::to_string(r.ms_per_step_repeats.size()) +
                         "; min " + Number(r.ms_per_step_min) + ", max " + Number(r.ms_per_step_max) + ")");
  row("max penetration", Number(r.max_penetration) + " m");
  row("min distance", Text(r.min_distance, "m"));
  row("iterations", r.iterations_mean ? Number(*r.iterations_mean) + " a step (at most " + Number(r.iterations_max) + ")" : "-");
  row("method residual", Text(r.residual_min, "(smallest)"));
  row("method stiffness", Text(r.stiffness_max, "(largest)"));
  row("fell through", r.fell_through ? std::to_string(*r.fell_through) + " bodies" : "-");
  row("final kinetic energy", Number(r.final_kinetic_energy) + " J");
  row("top displacement", Text(r.top_displacement, "m"));
  row("rebound height", Text(r.rebound_height, "m"));
  row("peak memory", Number(r.peak_rss_mb) + " MiB");
  row("status", r.status);
}

}  // namespace contactsim::bench
