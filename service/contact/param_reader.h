// Reads a method's text parameters into typed values with range checks.
// Errors name the parameter and the value; nothing is written to the
// caller's settings unless every parameter is valid (read into a copy, then
// commit on Finish().ok()).
#pragma once

#include <set>
#include <string>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/physics/validation.h"

namespace contactsim {

class ParamReader {
 public:
  ParamReader(const char* method, const ParamMap& params) : method_(method), params_(params) {}

  // Each reader leaves *value unchanged when the parameter is absent.
  void Double(const char* name, double lo, double hi, double* value);
  void Int(const char* name, int lo, int hi, int* value);
  void Bool(const char* name, bool* value);
  void Choice(const char* name, const std::vector<const char*>& choices, std::string* value);
  // One of `choices`, or a number in [lo, hi] written back by FormatValue.
  void ChoiceOrNumber(const char* name, const std::vector<const char*>& choices, double lo, double hi,
                      std::string* value);

  // The first error, or an error for a parameter no reader asked for.
  Status Finish() const;

 private:
  const std::string* Find(const char* name);
  // Writes `text` to *value when it is one of `choices`; else lists them,
  // comma separated, in *list for the error.
  static bool MatchChoice(const std::string& text, const std::vector<const char*>& choices, std::string* value,
                          std::string* list);
  void Fail(const std::string& message);

  std::string method_;
  const ParamMap& params_;
  std::set<std::string> known_;
  Status status_;
};


}  // namespace contactsim
