// Each contact method's parameters declared once, as a table of fields
// {name, member of the method's parameter struct, range or choices, unit,
// one line of doc}; the default is the struct's own initial value. The
// table parses a ParamMap (through ParamReader: every entry validated before
// anything changes, errors naming the parameter and the value), writes
// Params(), and describes itself (ParamDoc) for the README's table of
// contact methods (param_docs.h; tests/contact/param_docs_test.cpp compares).
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/contact/param_doc.h"
#include "service/contact/param_reader.h"
#include "service/physics/validation.h"

namespace contactsim {

template <class P>
struct ParamField {
  const char* name;
  std::variant<int P::*, double P::*, bool P::*, std::string P::*> member;
  ParamType type;
  double lo, hi;
  std::vector<const char*> choices;
  const char* unit;
  const char* doc;
};

template <class P>
ParamField<P> IntParam(const char* name, int P::*m, int lo, int hi, const char* unit, const char* doc) {
  return {name, m, ParamType::kInt, double(lo), double(hi), {}, unit, doc};
}
template <class P>
ParamField<P> DoubleParam(const char* name, double P::*m, double lo, double hi, const char* unit, const char* doc) {
  return {name, m, ParamType::kDouble, lo, hi, {}, unit, doc};
}
template <class P>
ParamField<P> BoolParam(const char* name, bool P::*m, const char* doc) {
  return {name, m, ParamType::kBool, 0.0, 0.0, {}, "", doc};
}
template <class P>
ParamField<P> ChoiceParam(const char* name, std::string P::*m, std::vector<const char*> choices, const char* doc) {
  return {name, m, ParamType::kChoice, 0.0, 0.0, std::move(choices), "", doc};
}
// one of `choices` or a number in [lo, hi], kept as text (FormatValue)
template <class P>
ParamField<P> ChoiceOrNumberParam(const char* name, std::string P::*m, std::vector<const char*> choices, double lo,
                                  double hi, const char* doc) {
  return {name, m, ParamType::kChoiceOrNumber, lo, hi, std::move(choices), "", doc};
}

template <class P>
class ParamTable {
 public:
  ParamTable(std::initializer_list<ParamField<P>> fields) : fields_(fields) {}

  // Reads `params` over a copy of `current`; on success stores the result
  // in *out (which may alias current), else leaves it and returns the first
  // error, or the error for a name no field declares.
  Status Parse(const char* method, const ParamMap& params, const P& current, P* out) const {
    P p = current;
    ParamReader r(method, params);
    for (const ParamField<P>& f : fields_) Read(f, r, &p);
    Status status = r.Finish();
    if (status.ok()) *out = p;
    return status;
  }

  ParamMap ToMap(const P& p) const {
    ParamMap map;
    for (const ParamField<P>& f : fields_) map[f.name] = Text(f, p);
    return map;
  }

  // In declaration order, with the defaults of P{}.
  std::vector<ParamDoc> Docs() const {
    const P defaults{};
    std::vector<ParamDoc> docs;
    for (const ParamField<P>& f : fields_) {
      ParamDoc d;
      d.name = f.name;
      d.type = f.type;
      d.lo = f.lo;
      d.hi = f.hi;
      d.choices.assign(f.choices.begin(), f.choices.end());
      d.unit = f.unit;
      d.default_value = Text(f, defaults);
      d.doc = f.doc;
      docs.push_back(d);
    }
    return docs;
  }

 private:
  static void Read(const ParamField<P>& f, ParamReader& r, P* p) {
    switch (f.type) {
      case ParamType::kInt:
        r.Int(f.name, static_cast<int>(f.lo), static_cast<int>(f.hi), &(p->*std::get<int P::*>(f.member)));
        break;
      case ParamType::kDouble: r.Double(f.name, f.lo, f.hi, &(p->*std::get<double P::*>(f.member))); break;
      case ParamType::kBool: r.Bool(f.name, &(p->*std::get<bool P::*>(f.member))); break;
      case ParamType::kChoice: r.Choice(f.name, f.choices, &(p->*std::get<std::string P::*>(f.member))); break;
      case ParamType::kChoiceOrNumber:
        r.ChoiceOrNumber(f.name, f.choices, f.lo, f.hi, &(p->*std::get<std::string P::*>(f.member)));
        break;
    }
  }

  static std::string Text(const ParamField<P>& f, const P& p) {
    switch (f.type) {
      case ParamType::kInt: return std::to_string(p.*std::get<int P::*>(f.member));
      case ParamType::kDouble: return FormatValue(p.*std::get<double P::*>(f.member));
      case ParamType::kBool: return p.*std::get<bool P::*>(f.member) ? "true" : "false";
      default: return p.*std::get<std::string P::*>(f.member);
    }
  }

  std::vector<ParamField<P>> fields_;
};

}  // namespace contactsim
