// A fresh folder under /tmp for one test, removed with everything in it at
// the end.
#pragma once

#include <stdlib.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
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

// Writes `text` to a file `name` in gtest's temporary folder and returns its
// path (a config or model file for a test to load).
inline std::string WriteTempFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace testing
}  // namespace contactsim
