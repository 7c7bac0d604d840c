#include "bench/tools/scene_bench/contactsim_engine.h"

#include <utility>

#include "service/contact/method_support.h"
#include "service/contact/sleep/island_sleep.h"

namespace contactsim::bench {
namespace {

class ContactsimEngine : public SceneEngine {
 public:
  ContactsimEngine(std::unique_ptr<ContactMethod> method, World world, bool sleep)
      : method_(std::move(method)), world_(std::move(world)) {
    world_.sleep.enabled = sleep;
    // the bench reads the steps' stats and the world, not the contacts'
    // values (run_scene.cpp, scene_metrics.cpp; contact_method.h)
    method_->RequestContactReport(false);
  }
  Status SetBroadphase(const std::string& name) { return detector_.SetBroadphase(name); }
  Status SetThreads(int threads) { return detector_.SetThreads(threads); }
  void SetManifoldReuse(bool on) { detector_.SetManifoldReuse(on); }
  void Step() override { stats_ = sleep_.Step(world_, *method_, detector_, &contacts_); }
  int Sleeping() const override { return sleep_.stats().sleeping; }
  std::optional<StepStats> LastStats() const override { return stats_; }
  const World& Sync() override { return world_; }
  ParamMap Params() const override { return method_->Params(); }

 private:
  std::unique_ptr<ContactMethod> method_;
  World world_;
  CollisionDetector detector_;
  IslandSleep sleep_;
  ContactSet contacts_;
  StepStats stats_;
};

}  // namespace

Status CreateContactsimEngine(const BenchOptions& options, const SceneSpec& scene, const World& world,
                              std::unique_ptr<SceneEngine>* out) {
  std::unique_ptr<ContactMethod> method;
  Status st = CreateContactMethod(options.method, &method);
  if (!st.ok()) return st;
  ParamMap params;
  if (scene.contact_method == options.method) params = scene.method_params;
  for (const auto& [key, value] : options.params) params[key] = value;
  if (!(st = method->SetParams(params)).ok()) return st;
  if (!(st = CheckMethodSupports(options.method, world)).ok()) return st;
  auto engine = std::make_unique<ContactsimEngine>(std::move(method), world, options.sleep);
  if (!(st = engine->SetBroadphase(options.broadphase)).ok()) return st;
  if (!(st = engine->SetThreads(options.threads)).ok()) return st;
  engine->SetManifoldReuse(options.manifold_reuse);
  *out = std::move(engine);
  return Status::Ok();
}

}  // namespace contactsim::bench
