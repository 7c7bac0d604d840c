// A contact method's parameter as the docs show it, apart from the struct
// that holds it (param_table.h declares both at once): name, type, range or
// choices, unit, default and one line of doc. ContactMethod::ParamDocs()
// lists them; param_docs.h writes the README's column from them.
#pragma once

#include <string>
#include <vector>

namespace contactsim {

enum class ParamType { kInt, kDouble, kBool, kChoice, kChoiceOrNumber };

struct ParamDoc {
  std::string name;
  ParamType type = ParamType::kDouble;
  double lo = 0.0, hi = 0.0;          // kInt, kDouble, kChoiceOrNumber: the range
  std::vector<std::string> choices;   // kChoice, kChoiceOrNumber: the words
  std::string unit;                   // "" when unitless
  std::string default_value;          // as Params() writes it
  std::string doc;
};

}  // namespace contactsim
