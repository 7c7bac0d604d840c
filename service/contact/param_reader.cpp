#include "service/contact/param_reader.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace contactsim {

const std::string* ParamReader::Find(const char* name) {
  known_.insert(name);
  const auto it = params_.find(name);
  return it == params_.end() ? nullptr : &it->second;
}

void ParamReader::Fail(const std::string& message) {
  if (status_.ok()) status_ = Status::InvalidArgument(message);
}

void ParamReader::Double(const char* name, double lo, double hi, double* value) {
  const std::string* text = Find(name);
  if (text == nullptr) return;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text->c_str(), &end);
  if (text->empty() || *end != '\0' || errno != 0 || !std::isfinite(v)) {
    Fail(method_ + " parameter " + name + " must be a finite number, got \"" + *text + "\"");
  } else if (v < lo || v > hi) {
    Fail(method_ + " parameter " + name + " must be in [" + FormatValue(lo) + ", " + FormatValue(hi) +
         "], got " + *text);
  } else {
    *value = v;
  }
}

void ParamReader::Int(const char* name, int lo, int hi, int* value) {
  const std::string* text = Find(name);
  if (text == nullptr) return;
  errno = 0;
  char* end = nullptr;
  const long v = std::strtol(text->c_str(), &end, 10);
  if (text->empty() || *end != '\0' || errno != 0) {
    Fail(method_ + " parameter " + name + " must be an integer, got \"" + *text + "\"");
  } else if (v < lo || v > hi) {
    Fail(method_ + " parameter " + name + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
         "], got " + *text);
  } else {
    *value = static_cast<int>(v);
  }
}

void ParamReader::Bool(const char* name, bool* value) {
  const std::string* text = Find(name);
  if (text == nullptr) return;
  if (*text == "true" || *text == "1") *value = true;
  else if (*text == "false" || *text == "0") *value = false;
  else Fail(method_ + " parameter " + name + " must be true or false, got \"" + *text + "\"");
}

bool ParamReader::MatchChoice(const std::string& text, const std::vector<const char*>& choices, std::string* value,
                              std::string* list) {
  for (const char* c : choices) {
    if (text == c) {
      *value = text;
      return true;
    }
    *list += list->empty() ? c : std::string(", ") + c;
  }
  return false;
}

void ParamReader::Choice(const char* name, const std::vector<const char*>& choices, std::string* value) {
  const std::string* text = Find(name);
  if (text == nullptr) return;
  std::string list;
  if (MatchChoice(*text, choices, value, &list)) return;
  Fail(method_ + " parameter " + name + " must be one of " + list + ", got \"" + *text + "\"");
}

void ParamReader::ChoiceOrNumber(const char* name, const std::vector<const char*>& choices, double lo, double hi,
                                 std::string* value) {
  const std::string* text = Find(name);
  if (text == nullptr) return;
  std::string words;
  if (MatchChoice(*text, choices, value, &words)) return;
  char* end = nullptr;
  std::strtod(text->c_str(), &end);
  if (text->empty() || *end != '\0') {
    Fail(method_ + " parameter " + name + " must be " + words + " or a number in [" + FormatValue(lo) + ", " +
         FormatValue(hi) + "], got \"" + *text + "\"");
    return;
  }
  // Double writes only a number in [lo, hi], with its own errors
  double number = -std::numeric_limits<double>::infinity();
  Double(name, lo, hi, &number);
  if (number >= lo) *value = FormatValue(number);
}

Status ParamReader::Finish() const {
  if (!status_.ok()) return status_;
  for (const auto& [name, value] : params_) {
    if (known_.count(name)) continue;
    std::string list;
    for (const std::string& k : known_) list += list.empty() ? k : ", " + k;
    return Status::InvalidArgument("unknown parameter \"" + name + "\" for contact method " + method_ +
                                   " (known: " + list + ")");
  }
  return Status::Ok();
}

}  // namespace contactsim
