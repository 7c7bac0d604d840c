// Where each link and joint of a model sits in its file, so that an error
// names the file, the element and the line ("robot.urdf: joint 'elbow'
// (line 42): ..."). The readers fill it from the XML as they parse.
#pragma once

#include <map>
#include <string>

namespace contactsim::model {

struct SourceMap {
  std::string file;                      // the path, or "<inline>"
  std::map<std::string, int> link_lines;   // link name -> line (1-based)
  std::map<std::string, int> joint_lines;  // joint name -> line

  std::string Link(const std::string& name) const { return Element("link", name, link_lines); }
  std::string Joint(const std::string& name) const { return Element("joint", name, joint_lines); }
  // "file: " for messages about the whole model.
  std::string File() const { return file + ": "; }

 private:
  std::string Element(const char* kind, const std::string& name, const std::map<std::string, int>& lines) const {
    std::string out = file + ": " + kind + " '" + name + "'";
    const auto it = lines.find(name);
    if (it != lines.end() && it->second > 0) out += " (line " + std::to_string(it->second) + ")";
    return out + ": ";
  }
};

}  // namespace contactsim::model
