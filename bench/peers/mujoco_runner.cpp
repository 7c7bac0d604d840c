// contactsim-bench-mujoco: a benchmark scene in MuJoCo (Debian
// libmujoco-dev), with the same flags, loop and metrics as contactsim-bench
// (service/tools/scene_bench).
//
// Translation: an MJCF model written in memory (option timestep = the
// scene's dt, gravity; everything else MuJoCo's default: Newton solver,
// 100 iterations, pyramidal cones, Euler integrator); static bodies and
// planes are world geoms, dynamic ones free bodies with the same mass and
// principal inertia. Friction: sliding mu per geom (MuJoCo takes the pair's
// max; every standard scene has one mu). MuJoCo has no restitution: its
// contacts are soft, a spring-damper in the reference acceleration set by
// solref = (timeconst, dampratio). We keep timeconst at its default 0.02 s
// and map restitution e to the damping ratio of a linear oscillator whose
// bounce loses that much speed, zeta = -ln e / sqrt(pi^2 + ln^2 e)
// (e = 0 gives zeta = 1, MuJoCo's default; e = 0.5 gives 0.2155). MuJoCo
// averages solref over the pair; the bounce scene gives both surfaces the
// same e. Methods: "newton" (default), "cg", "pgs" (mjOption.solver).
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <sstream>
#include <vector>

#include "bench/peers/peer_mirror.h"
#include "service/contact/param_reader.h"
#include "service/tools/scene_bench/scene_bench_main.h"

namespace contactsim::bench {
namespace {

constexpr double kPi = 3.141592653589793;
constexpr double kTimeConstant = 0.02;   // s, MuJoCo's default solref[0]
constexpr int kContactsPerBody = 20;     // contact buffer per body wanted (a box-box pair gives up to 8)
constexpr int kRowsPerContact = 4;       // pyramidal cone, condim 3
// MuJoCo 2.2 puts its solver stack and its constraint arrays, sized
// densely (efc_AR and its column indices njmax x njmax, 12 bytes an entry;
// efc_J, efc_JT and theirs njmax x nv, 24 bytes), in one buffer whose size is
// an int: past 2 GiB mj_makeData fails. The stack gets what the Newton solver
// needs for its nv x nv Hessian (3 nv^2 mjtNums, at least kMinStack; the
// default heuristic, 5 njmax^2, overflows the int) and the contact buffer
// the rest of kArenaBytes. A scene that needs more contacts stops with
// "contact buffer full".
constexpr double kArenaBytes = 2.0e9;
constexpr double kMinStack = 2e7;  // mjtNums

double StackSize(int nv) { return std::max(kMinStack, 3.0 * nv * nv); }

// Largest nconmax with 12 njmax^2 + 24 njmax nv <= kArenaBytes - 8 nstack, njmax = 4 nconmax.
int ContactBuffer(int bodies, int nv) {
  const double bytes = kArenaBytes - 8.0 * StackSize(nv);
  const double b = 2.0 * nv, c = -bytes / 12.0;
  const double njmax = (-b + std::sqrt(b * b - 4.0 * c)) / 2.0;
  return std::min(kContactsPerBody * bodies + 100, static_cast<int>(njmax / kRowsPerContact));
}

double DampingRatio(double restitution) {
  if (restitution <= 0.0) return 1.0;
  const double l = std::log(restitution);
  return -l / std::sqrt(kPi * kPi + l * l);
}

std::string Vec(const Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g", v.x(), v.y(), v.z());
  return buf;
}

std::string QuatText(const Quat& q) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g %.17g", q.w(), q.x(), q.y(), q.z());
  return buf;
}

std::string GeomText(const RigidBody& b) {
  std::ostringstream o;
  o.precision(17);
  o << "<geom";
  switch (b.shape.type) {
    case ShapeType::kSphere:
      o << " type=\"sphere\" size=\"" << b.shape.radius << "\"";
      break;
    case ShapeType::kBox:
      o << " type=\"box\" size=\"" << Vec(b.shape.half_extents) << "\"";
      break;
    default: {  // plane: MuJoCo's plane is the geom's z = 0, solid below
      Vec3 n;
      double offset;
      WorldPlane(b, &n, &offset);
      o << " type=\"plane\" size=\"0 0 1\" pos=\"" << Vec(offset * n) << "\" quat=\""
        << QuatText(Quat::FromTwoVectors(Vec3::UnitZ(), n)) << "\"";
    }
  }
  if (!b.IsDynamic() && !b.shape.IsPlane()) o << " pos=\"" << Vec(b.x) << "\" quat=\"" << QuatText(b.q) << "\"";
  o << " friction=\"" << b.material.friction << " 0.005 0.0001\" solref=\"" << kTimeConstant << " "
    << DampingRatio(b.material.restitution) << "\"/>";
  return o.str();
}

std::string ModelXml(const World& world) {
  std::ostringstream o;
  o.precision(17);
  int dynamic = 0;
  for (const RigidBody& b : world.bodies()) dynamic += b.IsDynamic();
  const int nconmax = ContactBuffer(static_cast<int>(world.bodies().size()), 6 * dynamic);
  const long nstack = static_cast<long>(StackSize(6 * dynamic));
  o << "<mujoco model=\"contactsim-bench\">\n<option timestep=\"" << world.dt << "\" gravity=\"" << Vec(world.gravity)
    << "\"/>\n<size nconmax=\"" << nconmax << "\" njmax=\"" << kRowsPerContact * nconmax << "\" nstack=\"" << nstack << "\"/>\n<worldbody>\n";
  for (const RigidBody& b : world.bodies()) {
    if (!b.IsDynamic()) {
      o << GeomText(b) << "\n";
      continue;
    }
    o << "<body pos=\"" << Vec(b.x) << "\" quat=\"" << QuatText(b.q) << "\"><freejoint/><inertial pos=\"0 0 0\" mass=\""
      << b.mass << "\" diaginertia=\"" << Vec(b.inertia_body.diagonal()) << "\"/>" << GeomText(b) << "</body>\n";
  }
  o << "</worldbody>\n</mujoco>\n";
  return o.str();
}

class MujocoEngine : public SceneEngine {
 public:
  MujocoEngine(const World& world, mjModel* model, const std::string& method)
      : mirror_(world), model_(model), data_(mj_makeData(model)), method_(method) {
    for (int i = 0; i < static_cast<int>(world.bodies().size()); ++i) {
      if (world.bodies()[i].IsDynamic()) index_.push_back(i);
    }
    // free body k (1-based body id k + 1) has qpos (x, q) at 7k, qvel (v_W, w_B) at 6k
    for (size_t k = 0; k < index_.size(); ++k) {
      const RigidBody& b = world.bodies()[index_[k]];
      const Vec3 v = b.LinearVelocity(), w_B = b.q.conjugate() * b.AngularVelocity();
      for (int j = 0; j < 3; ++j) {
        data_->qvel[6 * k + j] = v[j];
        data_->qvel[6 * k + 3 + j] = w_B[j];
      }
    }
  }
  ~MujocoEngine() override {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }

  void Step() override { mj_step(model_, data_); }

  const World& Sync() override {
    auto& out = mirror_.bodies();
    for (size_t k = 0; k < index_.size(); ++k) {
      const mjtNum* p = data_->qpos + 7 * k;
      const mjtNum* v = data_->qvel + 6 * k;
      const Quat q = Quat(p[3], p[4], p[5], p[6]).normalized();
      MirrorState(Vec3(p[0], p[1], p[2]), q, Vec3(v[0], v[1], v[2]), q * Vec3(v[3], v[4], v[5]), &out[index_[k]]);
    }
    return mirror_;
  }

  ParamMap Params() const override {
    return {{"solver", method_},
            {"nconmax", std::to_string(model_->nconmax)},
            {"iterations", std::to_string(model_->opt.iterations)},
            {"cone", model_->opt.cone == mjCONE_PYRAMIDAL ? "pyramidal" : "elliptic"},
            {"version", mj_versionString()}};
  }

  std::string Failure() const override {
    if (data_->warning[mjWARN_CONTACTFULL].number > 0) return "mujoco: contact buffer full";
    if (data_->warning[mjWARN_CNSTRFULL].number > 0) return "mujoco: constraint buffer full";
    if (data_->warning[mjWARN_BADQACC].number > 0) return "nan: mujoco reset the state after a bad qacc";
    return "";
  }

 private:
  World mirror_;
  mjModel* model_;
  mjData* data_;
  std::string method_;
  std::vector<int> index_;  // mirror index of each free body, in model order
};

// MuJoCo's default error handler waits for Enter; a benchmark must not.
void ExitOnMujocoError(const char* message) {
  std::fprintf(stderr, "mujoco error: %s\n", message);
  std::exit(1);
}

Status CreateMujocoEngine(const BenchOptions& options, const SceneSpec&, const World& world,
                          std::unique_ptr<SceneEngine>* out) {
  int solver;
  if (options.method == "newton") {
    solver = mjSOL_NEWTON;
  } else if (options.method == "cg") {
    solver = mjSOL_CG;
  } else if (options.method == "pgs") {
    solver = mjSOL_PGS;
  } else {
    return Status::NotFound("unknown MuJoCo method \"" + options.method + "\" (known: newton, cg, pgs)");
  }
  int iterations = -1;
  ParamReader reader(options.method.c_str(), options.params);
  reader.Int("iterations", 1, 100000, &iterations);
  Status st = reader.Finish();
  if (st.ok()) st = CheckPeerShapes(world, "MuJoCo");
  if (!st.ok()) return st;

  mju_user_error = ExitOnMujocoError;
  const std::string xml = ModelXml(world);
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  mj_makeEmptyFileVFS(vfs.get(), "scene.xml", static_cast<int>(xml.size()));
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), "scene.xml")], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* model = mj_loadXML("scene.xml", vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!model) return Status::InvalidArgument(std::string("MuJoCo rejected the generated model: ") + error);
  model->opt.solver = solver;
  if (iterations > 0) model->opt.iterations = iterations;
  *out = std::make_unique<MujocoEngine>(world, model, options.method);
  return Status::Ok();
}

}  // namespace
}  // namespace contactsim::bench

int main(int argc, char** argv) {
  contactsim::bench::RunnerInfo info;
  info.engine = "mujoco";
  info.description = std::string("contactsim-bench-mujoco: runs a contactsim scene file in MuJoCo ") + mj_versionString();
  info.default_method = "newton";
  info.methods = {"newton", "cg", "pgs"};
  info.factory = contactsim::bench::CreateMujocoEngine;
  return contactsim::bench::SceneBenchMain(argc, argv, info);
}
