// Tests of the parameter docs written from each method's declarations
// (service/contact/param_docs.h): README.md's "Contact methods" table and
// docs/physics.md's reference tables must match them, so neither can drift
// from what SetParams takes.
#include "service/contact/param_docs.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "service/contact/contact_method_registry.h"

namespace contactsim {
namespace {

// The cells of a markdown table row; "\|" inside a cell is not a separator.
std::vector<std::string> Cells(const std::string& row) {
  std::vector<std::string> cells;
  std::string cell;
  for (size_t i = 1; i < row.size(); ++i) {  // row[0] is the leading '|'
    if (row[i] == '|' && row[i - 1] != '\\') {
      const size_t first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
      cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
      cell.clear();
    } else {
      cell += row[i];
    }
  }
  return cells;
}

// README.md's "Contact methods" table: method name -> parameter column.
std::map<std::string, std::string> ReadmeColumns() {
  std::ifstream in(std::string(CONTACTSIM_SOURCE_DIR) + "/README.md");
  EXPECT_TRUE(in.good()) << "cannot read README.md";
  std::map<std::string, std::string> columns;
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) inside = line == "## Contact methods";
    if (!inside || line.rfind("| `", 0) != 0) continue;
    const std::vector<std::string> cells = Cells(line);
    if (cells.size() < 3) continue;
    columns[cells[0].substr(1, cells[0].size() - 2)] = cells[2];
  }
  return columns;
}

// Verifies that numbers read as a person writes them, not as printf does.
TEST(ParamDocsTest, NumbersReadAsWritten) {
  EXPECT_EQ(ReadableNumber(1e-5), "1e-5");
  EXPECT_EQ(ReadableNumber(1e6), "1e6");
  EXPECT_EQ(ReadableNumber(2.5e-7), "2.5e-7");
  EXPECT_EQ(ReadableNumber(0.001), "0.001");
  EXPECT_EQ(ReadableNumber(20), "20");
  EXPECT_EQ(ReadableNumber(0), "0");
}

// Verifies that a choice lists its default first and a number its unit.
TEST(ParamDocsTest, ChoicesStartWithTheDefaultAndNumbersCarryTheirUnit) {
  ParamDoc toi{"toi", ParamType::kChoice, 0, 0, {"bisection", "off", "regula_falsi"}, "", "off", ""};
  EXPECT_EQ(ReadmeParam(toi), "`toi` (`off` \\| `bisection` \\| `regula_falsi`)");
  ParamDoc slop{"slop", ParamType::kDouble, 0, 0.1, {}, "m", "0.001", ""};
  EXPECT_EQ(ReadmeParam(slop), "`slop` (0.001 m)");
  ParamDoc e{"restitution", ParamType::kChoiceOrNumber, 0, 1, {"material", "off"}, "", "material", ""};
  EXPECT_EQ(ReadmeParam(e), "`restitution` (`material` \\| `off` \\| 0 to 1)");
}

// Verifies that README.md's "Contact methods" table has one row per
// registered method and that each row's parameters are the declared ones,
// in declaration order, with their defaults and units.
TEST(ParamDocsTest, ReadmeTableMatchesTheDeclarations) {
  const std::map<std::string, std::string> readme = ReadmeColumns();
  std::map<std::string, bool> registered;
  for (const ContactMethodEntry& e : ContactMethodTable()) {
    registered[e.name] = true;
    const std::string expected = ReadmeParamColumn(e.create()->ParamDocs());
    const auto it = readme.find(e.name);
    ASSERT_NE(it, readme.end()) << "README.md's Contact methods table has no row for " << e.name;
    EXPECT_EQ(it->second, expected) << "README.md's parameters of " << e.name
                                    << " differ from the declarations; the column should read:\n"
                                    << expected;
  }
  for (const auto& [name, column] : readme) {
    EXPECT_TRUE(registered.count(name)) << "README.md lists a method " << name << " the registry does not have";
  }
}

// The reference table of a method's page, docs/methods/NAME.md: the table
// lines after the line that starts "Parameters of `name`", or "" when there
// is none.
std::string PhysicsTable(const std::string& method) {
  const std::string page = "docs/methods/" + method + ".md";
  std::ifstream in(std::string(CONTACTSIM_SOURCE_DIR) + "/" + page);
  EXPECT_TRUE(in.good()) << "cannot read " << page;
  const std::string marker = "Parameters of `" + method + "`";
  std::string line, table;
  bool found = false;
  while (std::getline(in, line)) {
    if (!found) {
      found = line.rfind(marker, 0) == 0;
      continue;
    }
    if (line.empty() && table.empty()) continue;
    if (line.rfind("|", 0) != 0) break;
    table += line + "\n";
  }
  return table;
}

// Verifies that each method's page has its parameter reference
// (default, range, meaning) exactly as the declarations write it.
TEST(ParamDocsTest, PhysicsReferenceTablesMatchTheDeclarations) {
  for (const ContactMethodEntry& e : ContactMethodTable()) {
    const std::string expected = ParamReferenceTable(e.create()->ParamDocs());
    EXPECT_EQ(PhysicsTable(e.name), expected)
        << "docs/methods/" << e.name << ".md's table after \"Parameters of `" << e.name
        << "`\" differs from the declarations; it should read:\n"
        << expected;
  }
}

// Verifies that every declared parameter is one Params() writes and
// SetParams takes back unchanged, and that its default is what a new
// method reports.
TEST(ParamDocsTest, DeclarationsAreWhatTheMethodTakesAndReports) {
  for (const ContactMethodEntry& e : ContactMethodTable()) {
    const std::unique_ptr<ContactMethod> m = e.create();
    const ParamMap params = m->Params();
    const std::vector<ParamDoc> docs = m->ParamDocs();
    EXPECT_EQ(params.size(), docs.size()) << e.name;
    for (const ParamDoc& d : docs) {
      ASSERT_TRUE(params.count(d.name)) << e.name << " " << d.name;
      EXPECT_EQ(params.at(d.name), d.default_value) << e.name << " " << d.name;
      EXPECT_FALSE(d.doc.empty()) << e.name << " " << d.name << " has no line of doc";
    }
    EXPECT_TRUE(m->SetParams(params).ok()) << e.name;
    EXPECT_EQ(m->Params(), params) << e.name;
  }
}

}  // namespace
}  // namespace contactsim
