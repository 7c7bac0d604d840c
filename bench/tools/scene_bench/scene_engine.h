// One engine stepping a benchmark scene: a contactsim contact method or a
// peer engine (bench/peers). The runner (run_scene.h) times Step() alone and
// reads every engine's state through the same World mirror, so the metrics
// (scene_metrics.h) are computed by the same code for every engine.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "service/collision/parallel_runner.h"
#include "service/contact/contact_method.h"
#include "service/physics/status.h"
#include "service/physics/world.h"
#include "service/scene/scene_spec.h"

namespace contactsim::bench {

// What a run was asked for (the command line, bench_options.h).
struct BenchOptions {
  std::string scene;             // path of the .pbtxt scene
  std::string method;            // engine-specific method name
  ParamMap params;               // --param key=value
  int steps = 0;                 // 0: the scene's `steps`
  std::string broadphase = "sap";
  int threads = DefaultThreadCount();  // of the collision detector (contactsim), of the thread pool (MuJoCo)
  bool sleep = false;            // settled islands sleep (--sleep; contactsim only): off, to time the solver
  bool manifold_reuse = true;    // touching polyhedron pairs keep their manifolds (--no-manifold-reuse; contactsim only)
  int repeat = 3;
  bool json = false;
  double max_seconds = 0.0;      // s of stepping per repeat before giving up; 0: no limit
};

class SceneEngine {
 public:
  virtual ~SceneEngine() = default;
  // Advances the engine by one step of the scene's dt (the timed part).
  virtual void Step() = 0;
  // Brings the mirror up to date (poses x, q and momenta P, L of every body,
  // in the scene's body order) and returns it. Not timed.
  virtual const World& Sync() = 0;
  // The method's effective parameters, for the report.
  virtual ParamMap Params() const = 0;
  // Trouble the engine itself reports after a step (a full contact buffer,
  // say); empty when none. The run stops there with this as its status.
  virtual std::string Failure() const { return ""; }
  // The contact method's own report of the last step (iterations, residual,
  // stiffness: contact_method.h); none for the peers.
  virtual std::optional<StepStats> LastStats() const { return std::nullopt; }
  // Bodies asleep after the last step (contactsim with --sleep); 0 otherwise.
  virtual int Sleeping() const { return 0; }
};

// Builds a fresh engine for the scene (called once per repeat). `world` is
// the scene as contactsim builds it (BuildWorld): shapes, poses, masses,
// inertias and materials for a peer to copy.
using EngineFactory = std::function<Status(const BenchOptions& options, const SceneSpec& scene,
                                           const World& world, std::unique_ptr<SceneEngine>* out)>;

}  // namespace contactsim::bench
