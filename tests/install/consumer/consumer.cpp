// Uses the installed client, its generated LCM headers and the mode table:
// prints the names of the run modes and the size of an encoded STATUS.
#include <cstdio>

#include "contactsim/client.h"
#include "contactsim/mode_names.h"
#include "contactsim/status_t.hpp"

int main() {
  contactsim::ClientOptions options;  // a client type from the installed header
  (void)options;
  contactsim::status_t status{};
  status.mode = contactsim::status_t::LOCKSTEP;
  std::printf("mode %s, STATUS of %d bytes\n", contactsim::NameOfMode(status.mode),
              status.getEncodedSize());
  return 0;
}
