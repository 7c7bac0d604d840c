// Tests of the server options' one declaration (service/server/server_options.h):
// every row is a field of the config file, the config's other fields are
// the ones that say where things are, docs/configuration.md lists the
// table as it is, and the shipped config runs with the defaults it always had.
#include "service/server/server_options.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "service/server/server_config.h"

namespace contactsim {
namespace {

using google::protobuf::FieldDescriptor;

// The config fields that are not options: where the server finds things.
const std::set<std::string> kSetupFields = {"scene",       "lcm_url",     "log_level",    "contact_method",
                                            "method_params", "journal_dir", "auth_key_file", "arm_driver",
                                            "wsg_driver",
                                            "model_path"};

// The protobuf type each kind of member is read from.
FieldDescriptor::CppType TypeOf(const ServerOption::Member& m) {
  switch (m.index()) {
    case 0: return FieldDescriptor::CPPTYPE_DOUBLE;
    case 1: case 5: return FieldDescriptor::CPPTYPE_INT32;
    case 2: return FieldDescriptor::CPPTYPE_INT64;
    case 3: return FieldDescriptor::CPPTYPE_BOOL;
    case 6: return FieldDescriptor::CPPTYPE_ENUM;
    default: return FieldDescriptor::CPPTYPE_STRING;
  }
}

// Verifies that each option names a config field of its type, and that
// every config field is an option or one of the setup fields.
TEST(ServerOptions, TableAndConfigFileDeclareTheSameFields) {
  const auto* d = proto::ServerConfig::descriptor();
  std::set<std::string> rows;
  for (const ServerOption& o : ServerOptionTable()) {
    const FieldDescriptor* fd = d->FindFieldByName(o.name);
    ASSERT_NE(fd, nullptr) << o.name;
    EXPECT_EQ(fd->cpp_type(), TypeOf(o.member)) << o.name;
    EXPECT_FALSE(fd->has_default_value()) << o.name << ": its default is the table's";
    EXPECT_TRUE(rows.insert(o.name).second) << o.name << " twice";
  }
  for (int i = 0; i < d->field_count(); ++i) {
    const std::string name = d->field(i)->name();
    EXPECT_TRUE(rows.count(name) + kSetupFields.count(name) == 1) << name;
  }
}

// Verifies that docs/configuration.md lists the table as it is.
TEST(ServerOptions, DocsListTheTable) {
  std::ifstream in(std::string(CONTACTSIM_SOURCE_DIR) + "/docs/configuration.md");
  ASSERT_TRUE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::string begin = "<!-- server-options:begin -->\n", end = "<!-- server-options:end -->";
  const size_t a = doc.find(begin), b = doc.find(end);
  ASSERT_TRUE(a != std::string::npos && b != std::string::npos);
  EXPECT_EQ(doc.substr(a + begin.size(), b - a - begin.size()), ServerOptionsMarkdown());
}

// Verifies that the shipped config/server.pbtxt runs with the options it
// ran with when the config file's schema held its own defaults.
TEST(ServerOptions, ShippedConfigKeepsItsEffectiveDefaults) {
  const std::string path = std::string(CONTACTSIM_SOURCE_DIR) + "/config/server.pbtxt";
  proto::ServerConfig config;
  ASSERT_TRUE(LoadServerConfig(path, &config).ok());
  ServerSetup setup;
  ASSERT_TRUE(MakeServerSetup(config, path, "", &setup).ok());
  const ServerOptions& o = setup.options;
  EXPECT_EQ(o.snapshot_every, 2400);
  EXPECT_TRUE(o.live_line);
  EXPECT_EQ(o.max_snapshots, 32);
  EXPECT_EQ(o.state_rate_hz, 60.0);
  EXPECT_EQ(o.contacts_rate_hz, 30.0);
  EXPECT_EQ(o.decode_limits.max_input_bytes, 8 << 20);
  EXPECT_EQ(o.journal_fsync, FsyncPolicy::kAlways);
  EXPECT_EQ(o.late_policy, LatePolicy::kWait);
  EXPECT_EQ(o.mode, RunMode::kRealtime);
  EXPECT_EQ(setup.log_level, "info");
}

// Verifies that a field the file sets reaches the options and that a value
// out of range or choice is refused naming the field and the value.
TEST(ServerOptions, SetFieldsAreReadAndCheckedNamingTheValue) {
  proto::ServerConfig config;
  config.set_snapshot_every_steps(0);
  config.set_live_line(false);
  config.set_journal_fsync("none");
  config.set_max_convex_points(16);
  ServerOptions o;
  ASSERT_TRUE(ReadServerOptions(config, &o).ok());
  EXPECT_EQ(o.snapshot_every, 0);
  EXPECT_FALSE(o.live_line);
  EXPECT_EQ(o.journal_fsync, FsyncPolicy::kNone);
  EXPECT_EQ(o.decode_limits.max_convex_points, 16);

  std::string field;
  config.set_broadphase("octree");
  Status st = ReadServerOptions(config, &o, &field);
  EXPECT_EQ(field, "broadphase");
  EXPECT_EQ(st.message(), "broadphase must be one of sap, naive, got \"octree\"");
  config.clear_broadphase();
  config.set_max_snapshots(0);
  st = ReadServerOptions(config, &o, &field);
  EXPECT_EQ(st.message(), "max_snapshots must be >= 1, got 0");
}

}  // namespace
}  // namespace contactsim
