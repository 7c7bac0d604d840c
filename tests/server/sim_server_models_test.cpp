// Tests of the model commands (model_cmd_t on <P>_MODEL_CMD) through the
// server logic and a recording transport: LOAD in the resolved form a
// journal keeps (a hand-made description), the reply's ids, MODEL_INFO,
// REMOVE as a whole, the refusals, and that snapshots, REWIND and journal
// recovery keep a model exactly.
#include <gtest/gtest.h>

#include <contactsim/model_info_t.hpp>

#include "service/proto/model.pb.h"
#include "service/scene/model_proto.h"
#include "tests/model/hand_made_models.h"
#include "tests/server/server_harness.h"
#include "tests/server/temp_dir.h"

namespace contactsim {
namespace {

using testing::ServerHarness;

model_cmd_t Load(const model::ModelDescription& d, const std::string& name = "") {
  model_cmd_t m{};
  m.client_id = "test";
  m.op = model_cmd_t::LOAD;
  m.format = model_cmd_t::FORMAT_RESOLVED;
  proto::ModelDescription p;
  SaveModelDescription(d, &p);
  const std::string bytes = p.SerializeAsString();
  m.resolved.assign(bytes.begin(), bytes.end());
  m.name = name;
  m.position[2] = 1.0;
  m.orientation[0] = 1.0;
  return m;
}

model_cmd_t Op(int8_t op, int64_t model_id = 0) {
  model_cmd_t m{};
  m.client_id = "test";
  m.op = op;
  m.model_id = model_id;
  m.orientation[0] = 1.0;
  return m;
}

ServerOptions ModelServerOptions() {
  ServerOptions o;
  o.prefix = "M";
  return o;
}

// Verifies that LOAD answers with the model id, one body per link and one
// joint per joint in the file's order, that MODEL_INFO names them, that a
// body or joint of the model cannot be removed alone, and that REMOVE takes
// out the whole model.
TEST(SimServerModelsTest, LoadReplyInfoAndRemove) {
  ServerHarness h(ModelServerOptions());
  reply_t r = h.Send(Load(model::testing::Arm()));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(r.ids, (std::vector<int64_t>{1, 1, 2, 3, 1, 2}));
  EXPECT_EQ(r.message, "loaded model \"arm\" 1: 3 links, 2 joints");
  const auto infos = h.transport.All<model_info_t>(h.server.Channel("MODEL_INFO"));
  ASSERT_FALSE(infos.empty());
  const model_info_t& info = infos.back();
  ASSERT_EQ(info.num_models, 1);
  EXPECT_EQ(info.models[0].link_names, (std::vector<std::string>{"base", "upper", "fore"}));
  EXPECT_EQ(info.models[0].link_bodies, (std::vector<int64_t>{1, 2, 3}));
  EXPECT_EQ(info.models[0].joint_names, (std::vector<std::string>{"shoulder", "elbow"}));
  EXPECT_EQ(info.models[0].joint_ids, (std::vector<int64_t>{1, 2}));
  EXPECT_EQ(info.models[0].joint_effort_limits[0], 10.0);

  body_cmd_t remove_body = h.Body(body_cmd_t::REMOVE, 2);
  r = h.Send(remove_body);
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION);
  EXPECT_NE(r.message.find("link \"upper\" of model \"arm\""), std::string::npos) << r.message;
  r = h.Send(Load(model::testing::Arm()));
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION) << r.message;
  r = h.Send(Load(model::testing::Arm(), "arm2"));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(r.ids[0], 2);

  r = h.Send(Op(model_cmd_t::REMOVE, 1));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(h.server.world().bodies().size(), 3u);
  EXPECT_EQ(h.server.world().joints().size(), 2u);
  EXPECT_EQ(h.transport.All<model_info_t>(h.server.Channel("MODEL_INFO")).back().num_models, 1);
  r = h.Send(Op(model_cmd_t::REMOVE, 1));
  EXPECT_EQ(r.code, reply_t::NOT_FOUND);
  EXPECT_EQ(r.message, "unknown model id 1");
  const size_t before = h.transport.All<model_info_t>(h.server.Channel("MODEL_INFO")).size();
  EXPECT_EQ(h.Send(Op(model_cmd_t::INFO)).code, reply_t::OK);
  EXPECT_EQ(h.transport.All<model_info_t>(h.server.Channel("MODEL_INFO")).size(), before + 1);
}

// Verifies that bad loads are refused with an error that says what is
// wrong and leave the world as it was: a bad joint between good ones,
// garbage in place of the resolved model, neither or both of path and
// text, a missing file, a text over the limit, a text that is no model,
// a bad orientation, an unknown op.
TEST(SimServerModelsTest, BadLoadsChangeNothing) {
  ServerHarness h(ModelServerOptions());
  const uint64_t before = HashWorldState(h.server.world());
  struct Case {
    model_cmd_t cmd;
    int32_t code;
    const char* expect;
  };
  model::ModelDescription bad = model::testing::Arm();
  bad.links.push_back(model::testing::SphereLink("hand", 0.2, 0.03, Vec3::Zero()));
  bad.joints.insert(bad.joints.begin() + 1, model::testing::Revolute("wrist", "fore", "nowhere", Vec3::Zero(),
                                                                     Vec3::UnitX()));
  std::vector<Case> cases;
  cases.push_back({Load(bad), reply_t::INVALID_ARGUMENT, "child link 'nowhere' is not in the model"});
  model_cmd_t garbage = Load(model::testing::Arm());
  garbage.resolved = {0xff, 0xff, 0xff};
  cases.push_back({garbage, reply_t::INVALID_ARGUMENT, "not a serialized model description"});
  model_cmd_t neither = Op(model_cmd_t::LOAD);
  cases.push_back({neither, reply_t::INVALID_ARGUMENT, "a path or the text"});
  model_cmd_t both = Op(model_cmd_t::LOAD);
  both.path = "a.urdf";
  both.text = "<robot/>";
  cases.push_back({both, reply_t::INVALID_ARGUMENT, "exactly one of them"});
  model_cmd_t missing = Op(model_cmd_t::LOAD);
  missing.path = "/nonexistent/robot.urdf";
  cases.push_back({missing, reply_t::NOT_FOUND, "cannot find '/nonexistent/robot.urdf'"});
  model_cmd_t huge = Op(model_cmd_t::LOAD);
  huge.text = "<robot>" + std::string(2 << 20, ' ') + "</robot>";
  cases.push_back({huge, reply_t::RESOURCE_EXHAUSTED, "exceeds max_model_text_bytes"});
  model_cmd_t junk = Op(model_cmd_t::LOAD);
  junk.text = "<html>not a model</html>";
  cases.push_back({junk, reply_t::INVALID_ARGUMENT, "neither URDF (<robot>) nor SDF (<sdf>)"});
  model_cmd_t turned = Load(model::testing::Arm());
  turned.orientation[0] = std::numeric_limits<double>::quiet_NaN();
  cases.push_back({turned, reply_t::INVALID_ARGUMENT, "orientation"});
  cases.push_back({Op(9), reply_t::INVALID_ARGUMENT, "op must be LOAD, REMOVE or INFO"});
  for (Case& c : cases) {
    const reply_t r = h.Send(c.cmd);
    EXPECT_EQ(r.code, c.code) << c.expect << ": " << r.message;
    EXPECT_NE(r.message.find(c.expect), std::string::npos) << r.message;
  }
  EXPECT_EQ(HashWorldState(h.server.world()), before);
  EXPECT_TRUE(h.server.world().bodies().empty());
  EXPECT_TRUE(h.server.world().models.empty());
  EXPECT_EQ(h.server.world().next_id, 1);
}

// Verifies that a model swinging under gravity is kept exactly: REWIND to
// a step after the load (snapshot + journal replay of the LOAD) repeats the
// run's hashes, REWIND to before it has no model, and a server restarted on
// the journal comes back with the same bodies and the same record.
TEST(SimServerModelsTest, RewindAndRecoveryKeepTheModel) {
  testing::TempDir dir;
  ServerOptions o = ModelServerOptions();
  o.journal_dir = dir.path();
  o.snapshot_every = 20;
  std::vector<uint64_t> run;
  uint64_t last = 0;
  {
    ServerHarness h(o);
    h.Step(5);
    ASSERT_EQ(h.Send(Load(model::testing::Arm())).code, reply_t::OK);
    run = h.Step(50);
    last = HashWorldState(h.server.world());
    scene_cmd_t rewind = h.Scene(scene_cmd_t::REWIND);
    rewind.target_step = 30;
    ASSERT_EQ(h.Send(rewind).code, reply_t::OK);
    EXPECT_EQ(HashWorldState(h.server.world()), run[30 - 6]);
    ASSERT_EQ(h.server.world().models.size(), 1u);
    EXPECT_EQ(h.server.world().models[0].links[2].body, 3);
    const std::vector<uint64_t> again = h.Step(25);
    EXPECT_EQ(again.back(), last);
    rewind.target_step = 3;
    ASSERT_EQ(h.Send(rewind).code, reply_t::OK);
    EXPECT_TRUE(h.server.world().models.empty());
    EXPECT_TRUE(h.server.world().bodies().empty());
    const std::vector<uint64_t> redo = h.Step(2);
    ASSERT_EQ(h.Send(Load(model::testing::Arm())).code, reply_t::OK);
    EXPECT_EQ(h.Step(50).back(), last);
  }
  ServerHarness recovered(o);
  EXPECT_EQ(HashWorldState(recovered.server.world()), last);
  ASSERT_EQ(recovered.server.world().models.size(), 1u);
  EXPECT_EQ(recovered.server.world().models[0].name, "arm");
  EXPECT_EQ(recovered.server.world().models[0].joints[1].joint, 2);
}

// Verifies that the world's record keeps every link's visual elements (pose
// in the link frame, geometry, mesh path and scale, colour) for viewers, and
// that a snapshot brings them back bit for bit through journal recovery.
TEST(SimServerModelsTest, TheRecordKeepsTheVisualsThroughASnapshot) {
  model::ModelDescription arm = model::testing::Arm();
  model::VisualElement box;
  box.origin.position = Vec3(0.1, -0.2, 0.3);
  box.origin.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  box.geometry.box_size = Vec3(0.1, 0.2, 0.3);
  box.rgba = Eigen::Vector4d(0.25, 0.5, 0.75, 1.0);
  model::VisualElement mesh;
  mesh.geometry.type = model::GeometryType::kMesh;
  mesh.geometry.mesh_path = "/meshes/forearm.dae";
  mesh.geometry.mesh_scale = Vec3(0.001, 0.001, 0.002);
  arm.links[1].visuals = {box};
  arm.links[2].visuals = {mesh, box};
  testing::TempDir dir;
  ServerOptions o = ModelServerOptions();
  o.journal_dir = dir.path();
  o.snapshot_every = 10;
  {
    ServerHarness h(o);
    ASSERT_EQ(h.Send(Load(arm)).code, reply_t::OK);
    h.Step(25);   // the load is before the snapshots of steps 10 and 20
  }
  ServerHarness recovered(o);
  ASSERT_EQ(recovered.server.world().models.size(), 1u);
  const std::vector<ModelLinkEntry>& links = recovered.server.world().models[0].links;
  ASSERT_EQ(links.size(), 3u);
  EXPECT_TRUE(links[0].visuals.empty());
  ASSERT_EQ(links[1].visuals.size(), 1u);
  ASSERT_EQ(links[2].visuals.size(), 2u);
  const ModelVisualEntry& b = links[2].visuals[1];
  EXPECT_EQ(b.geometry, static_cast<int>(model::GeometryType::kBox));
  EXPECT_EQ(b.position, box.origin.position);
  EXPECT_EQ(b.orientation.coeffs(), box.origin.orientation.coeffs());
  EXPECT_EQ(b.box_size, box.geometry.box_size);
  EXPECT_EQ(b.rgba, box.rgba);
  const ModelVisualEntry& m = links[2].visuals[0];
  EXPECT_EQ(m.geometry, static_cast<int>(model::GeometryType::kMesh));
  EXPECT_EQ(m.mesh_path, "/meshes/forearm.dae");
  EXPECT_EQ(m.mesh_scale, Vec3(0.001, 0.001, 0.002));
}

}  // namespace
}  // namespace contactsim

namespace contactsim {
namespace {

// Verifies the mimic contract through the server: a model whose elbow
// mimics its shoulder is refused under lcp (FAILED_PRECONDITION naming the
// methods that take it, nothing added), loads under impulse with the world
// joint a mimic, and then a switch to xpbd is refused and the method stays.
TEST(SimServerModelsTest, MimicJointsFollowTheMethodsContract) {
  ServerHarness h(ModelServerOptions());
  model::ModelDescription arm = model::testing::Arm();
  arm.joints[1].mimic = model::ModelMimic{"shoulder", -1.0, 0.0};
  scene_cmd_t method = h.Scene(scene_cmd_t::SET_METHOD);
  method.method = "lcp";
  ASSERT_EQ(h.Send(method).code, reply_t::OK);
  reply_t r = h.Send(Load(arm));
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION);
  EXPECT_EQ(r.message, "contact method lcp does not simulate mimic joints (joint couplings): choose impulse, "
                       "penalty or soft before loading a model with one");
  EXPECT_TRUE(h.server.world().bodies().empty());
  method.method = "impulse";
  ASSERT_EQ(h.Send(method).code, reply_t::OK);
  r = h.Send(Load(arm));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(h.server.world().FindJoint(2)->mimic.master, 1);
  EXPECT_EQ(h.server.world().FindJoint(2)->mimic.multiplier, -1.0);
  method.method = "xpbd";
  r = h.Send(method);
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION);
  EXPECT_NE(r.message.find("xpbd does not simulate mimic joints"), std::string::npos) << r.message;
  EXPECT_STREQ(h.server.method().Name(), "impulse");
}

}  // namespace
}  // namespace contactsim
