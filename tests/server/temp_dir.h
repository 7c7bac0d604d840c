// A fresh folder under /tmp for one test, removed with everything in it at
// the end.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <string>

namespace contactsim {
namespace testing {

class TempDir {
 public:
  TempDir() {
    char name[] = "/tmp/contactsim-test-XXXXXX";
    path_ = ::mkdtemp(name);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace testing
}  // namespace contactsim
