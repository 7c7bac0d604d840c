// contactsim-ctl's joint actuator subcommands (docs/actuators.md, "Joint
// channels"), as contactsim-py's:
//   joint state                     every joint's coordinate, rate and effort
//   joint set ID [--kp KP] [--target-position Q] ...   a joint's standing actuator fields
//   joint clear ID                  removes a joint's actuator
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

#include "contactsim/client.h"

// Adds the subcommands to `joint`; the chosen one sets `run`, which returns
// the exit status. `exit_code` turns a command's result into one.
void AddJointActuatorCommands(CLI::App* joint, std::function<int(contactsim::Client&)>* run,
                              int (*exit_code)(const contactsim::CommandResult&));
