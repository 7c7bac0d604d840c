#include "service/contact/param_docs.h"

#include <cmath>
#include <cstdlib>

#include "service/physics/validation.h"

namespace contactsim {

std::string ReadableNumber(double v) {
  if (v == 0.0 || !std::isfinite(v)) return FormatValue(v);
  const int exponent = static_cast<int>(std::floor(std::log10(std::abs(v))));
  if (std::abs(exponent) < 4) return FormatValue(v);
  // 1e6 rather than 1000000, 2.5e-5 rather than 2.5e-05
  return FormatValue(v / std::pow(10.0, exponent)) + "e" + std::to_string(exponent);
}

namespace {

std::string Quoted(const std::string& word) { return "`" + word + "`"; }

// the default first, then the other words, as the README's choices read
std::string Choices(const ParamDoc& doc) {
  std::string text = Quoted(doc.default_value);
  for (const std::string& c : doc.choices) {
    if (c != doc.default_value) text += " \\| " + Quoted(c);
  }
  return text;
}

std::string DefaultText(const ParamDoc& doc) {
  if (doc.type != ParamType::kDouble) return doc.default_value;
  const std::string value = ReadableNumber(std::strtod(doc.default_value.c_str(), nullptr));
  return doc.unit.empty() ? value : value + " " + doc.unit;
}

std::string Range(const ParamDoc& doc) {
  const std::string interval = "[" + ReadableNumber(doc.lo) + ", " + ReadableNumber(doc.hi) + "]";
  std::string words;
  for (const std::string& c : doc.choices) words += (words.empty() ? "" : ", ") + c;
  switch (doc.type) {
    case ParamType::kChoice: return words;
    case ParamType::kChoiceOrNumber: return words + ", " + interval;
    case ParamType::kBool: return "true, false";
    default: return interval;
  }
}

}  // namespace

std::string ReadmeParam(const ParamDoc& doc) {
  std::string value;
  switch (doc.type) {
    case ParamType::kChoice: value = Choices(doc); break;
    case ParamType::kChoiceOrNumber:
      value = Choices(doc) + " \\| " + ReadableNumber(doc.lo) + " to " + ReadableNumber(doc.hi);
      break;
    default: value = DefaultText(doc); break;
  }
  return Quoted(doc.name) + " (" + value + ")";
}

std::string ReadmeParamColumn(const std::vector<ParamDoc>& docs) {
  std::string column;
  for (const ParamDoc& d : docs) column += (column.empty() ? "" : ", ") + ReadmeParam(d);
  return column;
}

std::string ParamReferenceTable(const std::vector<ParamDoc>& docs) {
  std::string table = "| parameter | default | range | meaning |\n|---|---|---|---|\n";
  for (const ParamDoc& d : docs) {
    table += "| " + Quoted(d.name) + " | " + DefaultText(d) + " | " + Range(d) + " | " + d.doc + " |\n";
  }
  return table;
}

}  // namespace contactsim
