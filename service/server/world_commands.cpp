// SimServer's world commands (SCENE_CMD but snapshots and controllers):
// reset, scene load, gravity, time step, contact method, pause / resume /
// step and run mode. Simulation thread.
#include <spdlog/spdlog.h>

#include "service/contact/method_support.h"
#include "service/server/sim_server.h"

namespace contactsim {
Outcome SimServer::ApplyWorldCommand(Command& cmd) {
  using K = Command::Kind;
  switch (cmd.kind) {
    case K::kReset:
      CancelStepCommands("reset");
      world_.Clear();
      detector_.Reset();
      sleep_.Reset();
      method_->ResetCaches();
      StartOver();
      return Outcome::Done("world reset", true);
    case K::kLoadScene: {
      // built into a fresh world first, so that a failure leaves the old one
      World world;
      Status st = BuildWorld(*cmd.scene, &world);
      if (st.ok()) st = CheckMethodSupports((cmd.method ? cmd.method : method_)->Name(), world);
      if (!st.ok()) return Outcome::Failed(st);
      CancelStepCommands("scene loaded");
      world.sleep = world_.sleep;  // the run's setting, not the scene's
      ReplaceWorld(std::move(world), cmd.method ? cmd.method : method_);
      method_->ResetCaches();
      StartOver();
      return Outcome::Done("loaded " + cmd.scene_path + " (" + std::to_string(world_.bodies().size()) + " bodies)", true);
    }
    case K::kSetGravity:
      world_.gravity = cmd.gravity;
      world_.WakeAll();  // what rested under the old gravity may not under the new
      return Outcome::Done("gravity set", true);
    case K::kSetTimestep:
      world_.dt = cmd.dt;
      publisher_.UpdateRates(world_.dt);
      return Outcome::Done("time step set", true);
    case K::kSetMethod: {
      // a switch keeps every body's state and drops only the old method's caches
      const Status st = CheckMethodSupports(cmd.method->Name(), world_);
      if (!st.ok()) return Outcome::Failed(st);
      // the same method with new parameters keeps its state (warm starts,
      // friction anchors, placed overlaps), as a snapshot's restore does
      if (method_ != nullptr && method_->Name() == cmd.method->Name()) {
        const Status kept = cmd.method->LoadState(method_->SaveState());
        if (!kept.ok()) spdlog::warn("contact method {}: state not carried over: {}", method_->Name(), kept.message());
      }
      method_ = cmd.method;
      std::string text = std::string("contact method ") + method_->Name();
      for (const auto& [k, v] : method_->Params()) text += " " + k + "=" + v;
      spdlog::info("{}", text);
      // a body at rest under one method need not be under another (penalty
      // rests in a slight overlap that impulse pushes apart): the new method
      // settles the whole world again before anything sleeps
      const bool woke = world_.SleepingCount() > 0;
      world_.WakeAll();
      return Outcome::Done(text, woke);
    }
    case K::kPause:
      paused_ = true;
      // a running STEP stops at this step boundary, and says how far it got
      CancelStepCommands("cancelled by PAUSE from \"" + cmd.client_id + "\"");
      return Outcome::Done("paused", false);
    case K::kResume:
      if (!fault_.empty()) return Outcome::Failed(RefusedByFault());
      paused_ = false;
      reanchor_ = true;
      return Outcome::Done("running", false);
    case K::kStep: {
      if (!fault_.empty()) return Outcome::Failed(RefusedByFault());
      paused_ = true;
      steps_.Add(cmd, world_.step);  // reports progress at once: the client may wait as long as progress comes
      Outcome o;
      o.deferred = true;  // FinishStepCommands answers at the last step
      return o;
    }
    case K::kSetMode:
      mode_ = cmd.mode;
      real_time_factor_ = cmd.real_time_factor;
      reanchor_ = true;
      return Outcome::Done(std::string("mode ") + NameOf(mode_), false);
    default:
      return Outcome::Failed(Status::Internal("not a world command"));
  }
}

}  // namespace contactsim
