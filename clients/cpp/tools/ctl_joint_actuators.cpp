#include "ctl_joint_actuators.h"

#include <cstdio>
#include <memory>
#include <optional>

namespace {

struct ActuatorFlags {
  int64_t joint = 0;
  std::optional<double> torque, target_position, target_velocity, kp, kd, effort_limit, velocity_limit;

  contactsim::JointCommand ToCommand() const {
    contactsim::JointCommand c;
    c.joint_ids = {joint};
    const auto put = [](const std::optional<double>& v, std::vector<double>* out) {
      if (v) *out = {*v};
    };
    put(torque, &c.torque);
    put(target_position, &c.target_position);
    put(target_velocity, &c.target_velocity);
    put(kp, &c.kp);
    put(kd, &c.kd);
    put(effort_limit, &c.effort_limit);
    put(velocity_limit, &c.velocity_limit);
    return c;
  }
};

// One line per joint, as contactsim-py prints them.
int PrintJointState(contactsim::Client& client, int (*exit_code)(const contactsim::CommandResult&)) {
  contactsim::actuator_cmd_t m{};
  m.op = contactsim::actuator_cmd_t::STATE;
  const contactsim::CommandResult r = client.Send(m);
  if (!r.ok()) return exit_code(r);
  const auto js = client.WaitForJointState(
      [&](const contactsim::joint_state_t& s) { return s.step >= r.step; }, std::chrono::milliseconds(2000));
  if (!js) {
    std::fprintf(stderr, "no JOINT_STATE after the reply\n");
    return 2;
  }
  for (int i = 0; i < js->num_joints; ++i) {
    std::printf("joint %lld model %lld %s position %.9g velocity %.9g effort %.9g\n",
                static_cast<long long>(js->joint_ids[i]), static_cast<long long>(js->model_ids[i]),
                js->names[i].c_str(), js->positions[i], js->velocities[i], js->efforts[i]);
  }
  return 0;
}

}  // namespace

void AddJointActuatorCommands(CLI::App* joint, std::function<int(contactsim::Client&)>* run,
                              int (*exit_code)(const contactsim::CommandResult&)) {
  auto flags = std::make_shared<ActuatorFlags>();
  joint->add_subcommand("state", "print every hinge and prismatic joint's position, velocity and effort")
      ->callback([run, exit_code] { *run = [exit_code](contactsim::Client& c) { return PrintJointState(c, exit_code); }; });
  CLI::App* set = joint->add_subcommand("set", "set fields of a joint's standing actuator; the others stay");
  set->add_option("id", flags->joint, "joint id")->required();
  set->add_option("--torque", flags->torque, "N m or N, feed-forward");
  set->add_option("--target-position", flags->target_position, "rad or m (acts while kp > 0)");
  set->add_option("--target-velocity", flags->target_velocity, "rad/s or m/s (acts while kd > 0)");
  set->add_option("--kp", flags->kp, "N m/rad or N/m, >= 0");
  set->add_option("--kd", flags->kd, "N m s/rad or N s/m, >= 0");
  set->add_option("--effort-limit", flags->effort_limit, "N m or N, > 0");
  set->add_option("--velocity-limit", flags->velocity_limit, "rad/s or m/s, > 0");
  set->callback([run, exit_code, flags] {
    *run = [exit_code, flags](contactsim::Client& c) { return exit_code(c.SetJointActuators(flags->ToCommand())); };
  });
  CLI::App* clear = joint->add_subcommand("clear", "remove a joint's actuator");
  clear->add_option("id", flags->joint, "joint id")->required();
  clear->callback([run, exit_code, flags] {
    *run = [exit_code, flags](contactsim::Client& c) { return exit_code(c.ClearJointActuators({flags->joint})); };
  });
}
