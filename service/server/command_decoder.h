// Decodes LCM command payloads and runs every check that needs no world.
// Runs on the LCM thread, so bad input is answered at once and never
// reaches the simulation thread.
#pragma once

#include <contactsim/actuator_cmd_t.hpp>
#include <contactsim/body_cmd_t.hpp>
#include <contactsim/input_t.hpp>
#include <contactsim/joint_cmd_t.hpp>
#include <contactsim/ray_cast_t.hpp>
#include <contactsim/model_cmd_t.hpp>
#include <contactsim/scene_cmd_t.hpp>
#include <contactsim/sensor_cmd_t.hpp>

#include "service/physics/status.h"
#include "service/server/command.h"
#include "service/server/command_channels.h"

namespace contactsim {

// Turns a decoded body command into a Command; on error the status names the
// field and the value.
Status DecodeBodyCommand(const body_cmd_t& msg, const Material& default_material, Command* cmd);
Status DecodeSceneCommand(const scene_cmd_t& msg, Command* cmd);
// A lockstep controller's input (input_t): sizes agree, numbers finite.
Status DecodeInput(const input_t& msg, Command* cmd);
// Joint commands: every check of the settings but whether the bodies exist
// (CheckJointSettings); the simulation thread adds the joint.
Status DecodeJointCommand(const joint_cmd_t& msg, Command* cmd);
// Sensor commands: the name, and a range sensor's rays within `max_rays`;
// the simulation thread checks the body and that the name is free.
Status DecodeSensorCommand(const sensor_cmd_t& msg, int max_rays, Command* cmd);
// A batch of rays: 1 to `max_rays` rays, each checked by MakeRay.
Status DecodeRayCast(const ray_cast_t& msg, int max_rays, Command* cmd);
// Model commands (model_decoder.cpp): a LOAD reads the file or text and its
// meshes here, on the LCM thread, and stores the command in its resolved
// form (the model as read), so that the journal replays the same model
// whatever happens to the files later.
Status DecodeModelCommand(const model_cmd_t& msg, const DecodeContext& context, Command* cmd);
// SET or CLEAR of joints' actuators: DecodeActuatorUpdate's checks, and a
// SET names at least one field and one joint; STATE asks for JOINT_STATE.
Status DecodeActuatorCommand(const actuator_cmd_t& msg, Command* cmd);

}  // namespace contactsim
