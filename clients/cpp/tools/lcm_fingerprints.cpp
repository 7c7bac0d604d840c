// contactsim-lcm-fingerprints: prints "<type_name> <fingerprint>" for every
// contactsim LCM type, one per line, so that a test can check the C++ and
// Python code were generated from the same .lcm files.
//
// The fingerprint is T::getHash() as 16 lowercase hex digits: the same
// 64-bit value that leads every encoded message, big-endian, which is what
// Python's T._get_packed_fingerprint() returns as 8 bytes
// (struct.unpack(">Q", ...) gives this number). Type names are bare, as
// getTypeName() gives them ("state_t"), without the package.
#include <cinttypes>
#include <cstdio>

#include <contactsim/actuator_cmd_t.hpp>
#include <contactsim/body_cmd_t.hpp>
#include <contactsim/body_state_t.hpp>
#include <contactsim/contact_reading_t.hpp>
#include <contactsim/contact_t.hpp>
#include <contactsim/contacts_t.hpp>
#include <contactsim/input_t.hpp>
#include <contactsim/joint_cmd_t.hpp>
#include <contactsim/joint_command_t.hpp>
#include <contactsim/joint_state_t.hpp>
#include <contactsim/model_cmd_t.hpp>
#include <contactsim/model_entry_t.hpp>
#include <contactsim/model_info_t.hpp>
#include <contactsim/progress_t.hpp>
#include <contactsim/range_reading_t.hpp>
#include <contactsim/ray_cast_t.hpp>
#include <contactsim/ray_hits_t.hpp>
#include <contactsim/reply_t.hpp>
#include <contactsim/scene_cmd_t.hpp>
#include <contactsim/sensor_cmd_t.hpp>
#include <contactsim/sensors_t.hpp>
#include <contactsim/state_t.hpp>
#include <contactsim/status_t.hpp>

namespace {

template <typename T>
void Print() {
  std::printf("%s %016" PRIx64 "\n", T::getTypeName(),
              static_cast<uint64_t>(T::getHash()));
}

}  // namespace

int main() {
  Print<contactsim::body_cmd_t>();
  Print<contactsim::body_state_t>();
  Print<contactsim::contact_reading_t>();
  Print<contactsim::contact_t>();
  Print<contactsim::contacts_t>();
  Print<contactsim::input_t>();
  Print<contactsim::joint_cmd_t>();
  Print<contactsim::joint_command_t>();
  Print<contactsim::joint_state_t>();
  Print<contactsim::actuator_cmd_t>();
  Print<contactsim::model_cmd_t>();
  Print<contactsim::model_entry_t>();
  Print<contactsim::model_info_t>();
  Print<contactsim::progress_t>();
  Print<contactsim::range_reading_t>();
  Print<contactsim::ray_cast_t>();
  Print<contactsim::ray_hits_t>();
  Print<contactsim::reply_t>();
  Print<contactsim::scene_cmd_t>();
  Print<contactsim::sensor_cmd_t>();
  Print<contactsim::sensors_t>();
  Print<contactsim::state_t>();
  Print<contactsim::status_t>();
  return 0;
}
