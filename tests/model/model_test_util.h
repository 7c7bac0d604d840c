// Shared helpers of the model reader tests: the fixture folder, file text,
// and a small valid URDF to break one piece at a time.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

namespace contactsim::model::testing {

inline std::string DataDir() { return std::string(CONTACTSIM_SOURCE_DIR) + "/tests/model/data"; }

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A two-link URDF with `link2_body` as the second link's contents and
// `joint_body` as the joint's (type in `joint_type`).
inline std::string TwoLinkUrdf(const std::string& link2_body, const std::string& joint_type = "revolute",
                               const std::string& joint_body =
                                   "<parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 0 1\"/>"
                                   "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>") {
  return "<?xml version=\"1.0\"?>\n<robot name=\"two\">\n"
         "<link name=\"a\"/>\n"
         "<link name=\"b\">" + link2_body + "</link>\n"
         "<joint name=\"j\" type=\"" + joint_type + "\">" + joint_body + "</joint>\n"
         "</robot>\n";
}

inline std::string Inertial(const std::string& mass, const std::string& inertia) {
  return "<inertial><mass value=\"" + mass + "\"/><inertia " + inertia + "/></inertial>";
}

}  // namespace contactsim::model::testing
