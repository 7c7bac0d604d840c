// The SceneEngine of contactsim itself: any registered contact method
// (CreateContactMethod) with the chosen broadphase.
#pragma once

#include "bench/tools/scene_bench/scene_engine.h"

namespace contactsim::bench {

// Parameters: the scene's method_params when the scene names this method,
// then --param on top; validated by the method (an unknown name or a bad
// value is an error naming it).
Status CreateContactsimEngine(const BenchOptions& options, const SceneSpec& scene, const World& world,
                              std::unique_ptr<SceneEngine>* out);

}  // namespace contactsim::bench
