// contactsim-ctl: send one command to a running contactsim-server and print
// its reply, e.g.
//
//   contactsim-ctl status
//   contactsim-ctl add sphere --radius 0.1 --position 0 0 1 --mass 2
//   contactsim-ctl method impulse restitution=0.3
//   contactsim-ctl step 10
//   contactsim-ctl joint add hinge 3 0 --anchor 0 0 1 --axis 0 1 0 --limits -0.5 0.5
//   contactsim-ctl ray 0 0 5 0 0 -1 --max-distance 10
//   contactsim-ctl joint set 3 --target-position 0.5 --kp 200 --kd 20
//   contactsim-ctl model load /path/to/kuka_iiwa/model.urdf --name iiwa --fixed-base
//
// Exit status: 0 OK reply, 1 error reply, 2 no reply (timeout), LCM unusable
// or an unusable auth key file; CLI11's own codes for a bad command line.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "contactsim/client.h"
#include "contactsim/mode_names.h"
#include "contactsim/protocol.hpp"
#include "ctl_joint_actuators.h"

namespace {

// "[#########           ]  450/1000 steps  812 steps/s  0.7 s left" on
// stderr, redrawn in place as PROGRESS reports arrive.
void DrawProgress(const contactsim::progress_t& p) {
  constexpr int kWidth = 30;
  const double frac = p.total > 0 ? static_cast<double>(p.done) / static_cast<double>(p.total) : 0.0;
  const double rate = p.elapsed > 0.0 ? static_cast<double>(p.done) / p.elapsed : 0.0;
  const double left = rate > 0.0 ? static_cast<double>(p.total - p.done) / rate : 0.0;
  const int filled = static_cast<int>(frac * kWidth);
  std::fprintf(stderr, "\r[%s%s] %lld/%lld steps  %.0f steps/s  %.1f s left ", std::string(filled, '#').c_str(),
               std::string(kWidth - filled, ' ').c_str(), static_cast<long long>(p.done),
               static_cast<long long>(p.total), rate, left);
  std::fflush(stderr);
}

using contactsim::BodyOptions;
using contactsim::Client;
using contactsim::CommandResult;
using contactsim::ReplyCode;

constexpr int kExitErrorReply = 1;
constexpr int kExitNoReply = 2;

// A model's links and joints with their ids, as contactsim-py prints them.
void PrintModel(const contactsim::Model& m) {
  std::printf("model %lld %s\n", static_cast<long long>(m.id), m.name.c_str());
  for (size_t i = 0; i < m.links.size(); ++i) {
    std::printf("  link %-32s body %lld\n", m.links[i].c_str(), static_cast<long long>(m.link_bodies[i]));
  }
  for (size_t i = 0; i < m.joints.size(); ++i) {
    std::printf("  joint %-31s id %lld\n", m.joints[i].c_str(), static_cast<long long>(m.joint_ids[i]));
  }
}

int ExitCode(const CommandResult& result) {
  if (result.ok()) {
    std::cout << result << "\n";
    return 0;
  }
  std::cerr << result << "\n";
  return result.code == ReplyCode::kTimeout ||
                 result.code == ReplyCode::kTransport
             ? kExitNoReply
             : kExitErrorReply;
}

Eigen::Vector3d ToVector(const std::array<double, 3>& v) {
  return {v[0], v[1], v[2]};
}

void PrintStatus(const contactsim::status_t& s) {
  std::printf(
      "version: %s\nmode: %s\npaused: %s\nmethod: %s\nmethod_params: %s\nmethod_contract: %s\n"
      "time: %.6f s\nstep: %lld\ndt: %.6g s\nstep_rate: %.1f steps/s\n"
      "real_time_factor: %.3f (target %.3f)\nbodies: %d\ncontacts: %d\n"
      "max_penetration: %.3g m\nsolver_iterations: %d\n"
      "commands: %lld accepted, %lld rejected\nlast_error: %s\n",
      s.version.c_str(), contactsim::NameOfMode(s.mode), s.paused ? "yes" : "no",
      s.method.c_str(), s.method_params.c_str(), s.method_contract.c_str(), s.time,
      static_cast<long long>(s.step), s.dt, s.step_rate, s.real_time_factor,
      s.target_real_time_factor, s.num_bodies, s.num_contacts,
      s.max_penetration, s.solver_iterations,
      static_cast<long long>(s.commands_accepted),
      static_cast<long long>(s.commands_rejected), s.last_error.c_str());
}

// Command-line form of BodyOptions, shared by every `add` shape.
struct AddFlags {
  std::array<double, 3> position{0, 0, 0};
  std::array<double, 4> orientation{1, 0, 0, 0};
  std::array<double, 3> velocity{0, 0, 0};
  std::array<double, 3> angular_velocity{0, 0, 0};
  std::optional<double> mass, density, restitution, friction;
  bool fixed = false;
  bool kinematic = false;
  std::string name;

  BodyOptions ToOptions() const {
    BodyOptions options;
    options.position = ToVector(position);
    options.orientation = orientation;
    options.velocity = ToVector(velocity);
    options.angular_velocity = ToVector(angular_velocity);
    options.mass = mass;
    options.density = density;
    options.restitution = restitution;
    options.friction = friction;
    options.fixed = fixed;
    options.kinematic = kinematic;
    options.name = name;
    return options;
  }
};

void AddBodyFlags(CLI::App* app, AddFlags* flags) {
  app->add_option("--position,-p", flags->position, "m, centre of mass");
  app->add_option("--orientation,-q", flags->orientation,
                  "unit quaternion w x y z");
  app->add_option("--velocity,-v", flags->velocity, "m/s");
  app->add_option("--angular-velocity,-w", flags->angular_velocity, "rad/s");
  app->add_option("--mass,-m", flags->mass, "kg");
  app->add_option("--density,-d", flags->density, "kg/m^3");
  app->add_option("--restitution,-e", flags->restitution, "in [0, 1]");
  app->add_option("--friction,-f", flags->friction, "Coulomb coefficient");
  app->add_flag("--fixed", flags->fixed, "static body");
  app->add_flag("--kinematic", flags->kinematic, "infinite mass, moves with its velocity");
  app->add_option("--name,-n", flags->name, "label");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Send one command to contactsim-server and print its reply."};
  app.require_subcommand(1);
  contactsim::ClientOptions options;
  double timeout_s = 2.0;
  app.add_option("--lcm-url", options.url,
                 "LCM URL (default: $LCM_DEFAULT_URL, else the project default)");
  app.add_option("--prefix", options.prefix, "channel prefix")
      ->capture_default_str();
  app.add_option("--timeout", timeout_s, "s to wait for a reply")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  std::string auth_key_file;
  CLI::Option* auth_opt = app.add_option(
      "--auth-key-file", auth_key_file,
      "sign commands and check the server's signatures with this key "
      "(default: $CONTACTSIM_AUTH_KEY_FILE; docs/protocol.md, Authentication)");

  // Each subcommand sets `run`, which needs the Client that exists only
  // after parsing (the URL and prefix are options too).
  std::function<int(Client&)> run;

  app.add_subcommand("status", "print the server's latest STATUS")
      ->callback([&] {
        run = [&](Client& client) {
          const auto timeout = std::chrono::duration_cast<
              std::chrono::milliseconds>(std::chrono::duration<double>(timeout_s));
          // STATUS comes at ~1 Hz, so the wait is at least a second.
          if (!client.WaitForServer(std::max(timeout, std::chrono::milliseconds(1500)))) {
            std::cerr << "no STATUS on " << client.Channel(contactsim::protocol::kStatus);
            if (client.auth_failures() > 0) std::cerr << " (dropped, last: " << client.last_auth_failure() << ")";
            std::cerr << "\n";
            return kExitNoReply;
          }
          PrintStatus(*client.LatestStatus());
          return 0;
        };
      });

  CLI::App* add = app.add_subcommand("add", "add a body; prints its id");
  add->require_subcommand(1);
  AddFlags add_flags;
  double radius = 0.0;
  std::array<double, 3> half_extents{0, 0, 0};
  std::array<double, 3> normal{0, 0, 1};
  double offset = 0.0;
  CLI::App* sphere = add->add_subcommand("sphere", "add a sphere");
  sphere->add_option("--radius,-r", radius, "m")->required();
  AddBodyFlags(sphere, &add_flags);
  sphere->callback([&] {
    run = [&](Client& client) {
      return ExitCode(client.AddSphere(radius, add_flags.ToOptions()).status);
    };
  });
  CLI::App* box = add->add_subcommand("box", "add a box");
  box->add_option("--half-extents,-x", half_extents, "m, along body x y z")
      ->required();
  AddBodyFlags(box, &add_flags);
  box->callback([&] {
    run = [&](Client& client) {
      return ExitCode(
          client.AddBox(ToVector(half_extents), add_flags.ToOptions()).status);
    };
  });
  std::string mesh_path;
  double mesh_scale = 1.0;
  CLI::App* mesh = add->add_subcommand("mesh", "add a static triangle mesh from a file the server reads (OBJ, STL, PLY, DAE)");
  mesh->add_option("path", mesh_path, "mesh file")->required();
  mesh->add_option("--scale", mesh_scale, "times the file's vertices")->capture_default_str();
  AddBodyFlags(mesh, &add_flags);
  mesh->callback([&] {
    run = [&](Client& client) {
      return ExitCode(client.AddMeshFile(mesh_path, mesh_scale, add_flags.ToOptions()).status);
    };
  });
  std::string map_path;
  std::vector<double> map_spacing{1.0, 1.0};
  contactsim::HeightMapOptions map;
  CLI::App* field = add->add_subcommand(
      "heightfield", "add a static heightfield from a height map the server reads (16-bit greyscale PNG, or raw "
                     "little-endian uint16 with --rows and --cols)");
  field->add_option("path", map_path, "height map file")->required();
  field->add_option("--spacing", map_spacing, "m between samples along x and y")->expected(2)->capture_default_str();
  field->add_option("--rows", map.rows, "a raw file's rows (along y)");
  field->add_option("--cols", map.cols, "a raw file's columns (along x)");
  field->add_option("--scale", map.scale, "m at the largest sample, 65535")->capture_default_str();
  field->add_option("--offset", map.offset, "m at sample 0")->capture_default_str();
  AddBodyFlags(field, &add_flags);
  field->callback([&] {
    run = [&](Client& client) {
      return ExitCode(
          client.AddHeightfieldFile(map_path, map_spacing[0], map_spacing[1], map, add_flags.ToOptions()).status);
    };
  });
  CLI::App* plane = add->add_subcommand("plane", "add a static plane n.p = offset");
  plane->add_option("--normal", normal, "outward normal")->capture_default_str();
  plane->add_option("--offset", offset, "m")->capture_default_str();
  AddBodyFlags(plane, &add_flags);
  plane->callback([&] {
    run = [&](Client& client) {
      return ExitCode(
          client.AddPlane(ToVector(normal), offset, add_flags.ToOptions()).status);
    };
  });

  int64_t body_id = 0;
  app.add_subcommand("remove", "remove a body")
      ->callback([&] {
        run = [&](Client& client) { return ExitCode(client.RemoveBody(body_id)); };
      })
      ->add_option("id", body_id, "body id")
      ->required();

  CLI::App* joint = app.add_subcommand("joint", "add or remove a joint");
  joint->require_subcommand(1);
  const std::map<std::string, contactsim::JointType> joint_types = {
      {"distance", contactsim::JointType::kDistance},
      {"ball", contactsim::JointType::kBall},
      {"hinge", contactsim::JointType::kHinge},
      {"fixed", contactsim::JointType::kFixed},
      {"prismatic", contactsim::JointType::kPrismatic}};
  contactsim::JointType joint_type = contactsim::JointType::kBall;
  int64_t body_a = 0, body_b = 0;
  std::array<double, 3> anchor{0, 0, 0}, axis{0, 0, 0};
  std::optional<double> length;
  std::vector<double> limits;
  std::optional<double> damping, friction;
  CLI::App* joint_add = joint->add_subcommand("add", "add a joint; prints its id");
  joint_add->add_option("kind", joint_type, "distance | ball | hinge | fixed | prismatic")
      ->required()
      ->transform(CLI::CheckedTransformer(joint_types, CLI::ignore_case));
  joint_add->add_option("body_a", body_a, "body id")->required();
  joint_add->add_option("body_b", body_b, "body id, or 0 for the world")
      ->capture_default_str();
  joint_add->add_option("--anchor,-a", anchor,
                        "m, world: the joint point (distance: the point on body_b)")
      ->required();
  CLI::Option* axis_opt = joint_add->add_option("--axis", axis, "world, hinge and prismatic");
  joint_add->add_option("--length,-l", length, "m, distance only (default: current)");
  joint_add->add_option("--limits", limits, "lower upper: hinge (rad) and prismatic (m)")
      ->expected(2);
  joint_add->add_option("--damping", damping, "N m s/rad (hinge) or N s/m (prismatic)");
  joint_add->add_option("--friction", friction, "N m (hinge) or N (prismatic), Coulomb");
  joint_add->callback([&] {
    run = [&](Client& client) {
      contactsim::JointOptions joint_options;
      if (axis_opt->count() > 0) joint_options.axis = ToVector(axis);
      joint_options.length = length;
      if (limits.size() == 2) joint_options.limits = std::make_pair(limits[0], limits[1]);
      joint_options.damping = damping;
      joint_options.friction = friction;
      return ExitCode(client
                          .AddJoint(joint_type, body_a, body_b, ToVector(anchor),
                                    joint_options)
                          .status);
    };
  });
  int64_t joint_id = 0;
  joint->add_subcommand("remove", "remove a joint")
      ->callback([&] {
        run = [&](Client& client) { return ExitCode(client.RemoveJoint(joint_id)); };
      })
      ->add_option("id", joint_id, "joint id")
      ->required();
  AddJointActuatorCommands(joint, &run, &ExitCode);

  std::array<double, 3> ray_origin{0, 0, 0}, ray_direction{0, 0, 0};
  double ray_max_distance = 100.0;
  std::vector<int64_t> ray_ignore;
  CLI::App* ray = app.add_subcommand("ray", "cast one ray; prints what it hits (docs/protocol.md, Ray casts)");
  ray->add_option("origin", ray_origin, "m, world")->required();
  ray->add_option("direction", ray_direction, "world, any length")->required();
  ray->add_option("--max-distance", ray_max_distance, "m")->capture_default_str();
  ray->add_option("--ignore", ray_ignore, "body ids the ray passes through");
  ray->callback([&] {
    run = [&](Client& client) {
      const auto r = client.RayCast({ToVector(ray_origin)}, {ToVector(ray_direction)}, {ray_max_distance}, ray_ignore);
      if (!r.ok()) return ExitCode(r.status);
      const contactsim::ray_hits_t& h = r.value;
      if (!h.hit[0]) {
        std::printf("miss\n");
        return 0;
      }
      std::printf("hit body %lld distance %.9g point %.9g %.9g %.9g normal %.9g %.9g %.9g\n",
                  static_cast<long long>(h.body_ids[0]), h.distances[0], h.points[0][0], h.points[0][1],
                  h.points[0][2], h.normals[0][0], h.normals[0][1], h.normals[0][2]);
      return 0;
    };
  });

  CLI::App* sensor = app.add_subcommand("sensor", "add a contact sensor or remove a sensor");
  sensor->require_subcommand(1);
  int64_t sensor_body = 0;
  std::string sensor_name;
  CLI::App* sensor_contact =
      sensor->add_subcommand("contact", "the contact wrench a body receives each step, on SENSORS");
  sensor_contact->add_option("body", sensor_body, "body id")->required();
  sensor_contact->add_option("name", sensor_name, "sensor name")->required();
  sensor_contact->callback([&] {
    run = [&](Client& client) { return ExitCode(client.AddContactSensor(sensor_body, sensor_name)); };
  });
  sensor->add_subcommand("remove", "remove a sensor")
      ->callback([&] {
        run = [&](Client& client) { return ExitCode(client.RemoveSensor(sensor_name)); };
      })
      ->add_option("name", sensor_name, "sensor name")
      ->required();

  CLI::App* model = app.add_subcommand("model", "load, remove or list robot models");
  model->require_subcommand(1);
  std::string model_path;
  contactsim::ModelOptions model_options;
  std::array<double, 3> model_position{0, 0, 0};
  CLI::App* model_load =
      model->add_subcommand("load", "load a URDF or SDF model; prints its links and joints with their ids");
  model_load->add_option("path", model_path, "model file (on the server's host, or among its model paths)")
      ->required();
  model_load->add_option("--name", model_options.name, "the model's name in the world (default: the file's)");
  model_load->add_option("--position", model_position, "m, world: the root link's origin");
  model_load->add_option("--orientation", model_options.orientation, "(w, x, y, z): the root link's orientation");
  model_load->add_flag("--fixed-base", model_options.fixed_base, "the root link is static");
  model_load->add_flag("--self-collide", model_options.self_collide, "the model's links collide with each other");
  model_load->callback([&] {
    run = [&](Client& client) {
      model_options.position = ToVector(model_position);
      const contactsim::Result<contactsim::Model> r = client.LoadModel(model_path, model_options);
      if (r.ok()) PrintModel(r.value);
      return ExitCode(r.status);
    };
  });
  int64_t model_id = 0;
  model->add_subcommand("remove", "remove a model with its bodies and joints")
      ->callback([&] {
        run = [&](Client& client) { return ExitCode(client.RemoveModel(model_id)); };
      })
      ->add_option("id", model_id, "model id")
      ->required();
  model->add_subcommand("list", "list the loaded models")->callback([&] {
    run = [&](Client& client) {
      const contactsim::Result<std::vector<contactsim::Model>> r = client.Models();
      for (const contactsim::Model& m : r.value) PrintModel(m);
      return ExitCode(r.status);
    };
  });

  std::string method;
  std::vector<std::string> params;
  CLI::App* method_cmd =
      app.add_subcommand("method", "switch the contact method");
  method_cmd->add_option("name", method, "method name, e.g. impulse")->required();
  method_cmd->add_option("params", params, "parameters as key=value");
  method_cmd->callback([&] {
    run = [&](Client& client) {
      std::map<std::string, std::string> named;
      for (const std::string& param : params) {
        const size_t eq = param.find('=');
        if (eq == std::string::npos || eq == 0) {
          std::cerr << "parameter must be key=value, got \"" << param << "\"\n";
          return kExitErrorReply;
        }
        named[param.substr(0, eq)] = param.substr(eq + 1);
      }
      return ExitCode(client.SetContactMethod(method, named));
    };
  });

  app.add_subcommand("pause", "pause the run")->callback([&] {
    run = [](Client& client) { return ExitCode(client.Pause()); };
  });
  app.add_subcommand("resume", "resume the run")->callback([&] {
    run = [](Client& client) { return ExitCode(client.Resume()); };
  });
  app.add_subcommand("reset", "empty the world")->callback([&] {
    run = [](Client& client) { return ExitCode(client.Reset()); };
  });
  int32_t steps = 1;
  app.add_subcommand("step", "take N steps, then stay paused")
      ->callback([&] {
        run = [&](Client& client) {
          const bool bar = isatty(fileno(stderr));
          const CommandResult r = client.Step(steps, bar ? DrawProgress : Client::ProgressCallback{});
          if (bar) std::fputc('\n', stderr);
          return ExitCode(r);
        };
      })
      ->add_option("n", steps, "number of steps")
      ->required();

  CLI11_PARSE(app, argc, argv);
  options.reply_timeout = std::chrono::duration_cast<std::chrono::milliseconds>(
      std::chrono::duration<double>(timeout_s));
  if (auth_opt->count() > 0) options.auth_key_file = auth_key_file;
  Client client(options);
  if (!client.good()) {
    std::cerr << "contactsim-ctl: " << client.error() << "\n";
    return kExitNoReply;
  }
  return run(client);
}
