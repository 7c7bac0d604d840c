// The README's column of a contact method's parameters, written from its
// declarations (ContactMethod::ParamDocs(), param_table.h), so that the
// README cannot drift from what SetParams takes: tests/contact/
// param_docs_test.cpp compares README.md's "Contact methods" table with it,
// and each method page's parameter table (docs/methods/NAME.md) with
// ParamReferenceTable.
#pragma once

#include <string>
#include <vector>

#include "service/contact/param_doc.h"

namespace contactsim {

// A number as a reader writes it: 1e-5, 0.001, 20, 1e6.
std::string ReadableNumber(double v);

// "`name` (default unit)" for one parameter; a choice lists its words with
// the default first: "`toi` (`regula_falsi` \| `bisection` \| `off`)".
std::string ReadmeParam(const ParamDoc& doc);

// Every parameter of a method, in declaration order, comma separated.
std::string ReadmeParamColumn(const std::vector<ParamDoc>& docs);

// A markdown table of a method's parameters, one row each: | `name` |
// default | range | meaning |, with its header (docs/methods/NAME.md).
std::string ParamReferenceTable(const std::vector<ParamDoc>& docs);

}  // namespace contactsim
