// contactsim-fuzz-seeds DIR: writes one valid message of every op of every
// command channel as the fuzz targets' starting corpus:
// DIR/<suffix>/<n> for the decoder targets, and DIR/apply/<n> (channel
// index byte + message) for the apply target.
#include <fstream>
#include <iostream>
#include <string>
#include <sys/stat.h>

#include "service/server/command_channels.h"
#include "tests/server/command_messages.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: contactsim-fuzz-seeds DIR\n";
    return 2;
  }
  const std::string dir = argv[1];
  ::mkdir(dir.c_str(), 0755);
  ::mkdir((dir + "/apply").c_str(), 0755);
  const auto& channels = contactsim::CommandChannels();
  int n = 0;
  for (const auto& m : contactsim::testing::SampleCommandMessages()) {
    const std::string sub = dir + "/" + m.suffix;
    ::mkdir(sub.c_str(), 0755);
    std::ofstream(sub + "/" + std::to_string(n), std::ios::binary) << m.bytes;
    char index = 0;
    for (size_t i = 0; i < channels.size(); ++i) {
      if (m.suffix == channels[i].suffix) index = static_cast<char>(i);
    }
    std::ofstream(dir + "/apply/" + std::to_string(n), std::ios::binary) << index << m.bytes;
    ++n;
  }
  std::cout << "wrote " << n << " seeds to " << dir << "\n";
  return 0;
}
