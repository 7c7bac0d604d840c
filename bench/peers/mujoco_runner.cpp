// contactsim-bench-mujoco: a benchmark scene in MuJoCo (the mujoco-core
// wheel in .venv, clients/python/requirements.txt), with the same flags,
// loop and metrics as contactsim-bench (bench/tools/scene_bench).
//
// Translation: an MJCF model written in memory (option timestep = the
// scene's dt, gravity; everything else MuJoCo's default: Newton solver,
// 100 iterations, pyramidal cones, Euler integrator, islands on, sleeping
// off); static bodies and planes are world geoms, dynamic ones free bodies
// with the same mass and principal inertia. Friction: sliding mu per geom
// (MuJoCo takes the pair's max; every standard scene has one mu). MuJoCo has
// no restitution: its contacts are soft, a spring-damper in the reference
// acceleration set by solref = (timeconst, dampratio). We keep timeconst at
// its default 0.02 s and map restitution e to the damping ratio of a linear
// oscillator whose bounce loses that much speed,
// zeta = -ln e / sqrt(pi^2 + ln^2 e) (e = 0 gives zeta = 1, MuJoCo's
// default; e = 0.5 gives 0.2155). MuJoCo averages solref over the pair; the
// bounce scene gives both surfaces the same e. Methods: "newton" (default),
// "cg", "pgs" (mjOption.solver). --threads N > 1 gives the mjData a thread
// pool (mju_threadpool), which spreads collision detection and the solve of
// separate constraint islands over N threads.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench/peers/peer_mirror.h"
#include "bench/tools/scene_bench/scene_bench_main.h"
#include "service/contact/param_reader.h"

namespace contactsim::bench {
namespace {

constexpr double kPi = 3.141592653589793;
constexpr double kTimeConstant = 0.02;   // s, MuJoCo's default solref[0]
// MuJoCo lays out contacts, constraint rows (sparse Jacobians once nv >= 60)
// and its solver's stack, with Newton's sparse Cholesky factor of the
// Hessian, in one arena of <size memory> bytes that mj_makeData allocates
// once (MuJoCo's XML reference, size/memory); a step that runs out drops
// contacts or constraints, or leaves Newton for CG, and warns, and the run
// stops there (Failure()). Only the pages a step touches count toward the
// process's memory. The factor is what can grow: the 1,000-sphere pile is
// one island whose factor fills in toward dense (6,030 dofs: 145 MB as a
// dense lower triangle). 512 KiB a body leaves room for that; measured use
// was at most 51 MiB on the 1,000-body scenes (box_rain under Newton, 15
// under CG), 9 MiB on box_pyramid and 263 MiB in 30 Newton steps of the
// 5,050-box pyramid (BENCHMARKS.md, "MuJoCo on the larger scenes, bounded
// runs").
constexpr double kArenaBytesPerBody = 512.0 * 1024;
constexpr int kMinArenaMb = 64;

int DefaultArenaMb(int bodies) {
  return std::max(kMinArenaMb, static_cast<int>(std::ceil(kArenaBytesPerBody * bodies / (1 << 20))));
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

std::string ModelXml(const World& world, int arena_mb) {
  std::ostringstream o;
  o.precision(17);
  o << "<mujoco model=\"contactsim-bench\">\n<option timestep=\"" << world.dt << "\" gravity=\"" << Vec(world.gravity)
    << "\"/>\n<size memory=\"" << arena_mb << "M\"/>\n<worldbody>\n";
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
  MujocoEngine(const World& world, mjModel* model, const std::string& method, int threads)
      : mirror_(world), model_(model), data_(mj_makeData(model)), method_(method), threads_(threads) {
    // the stepping thread takes tasks too (mju_numThread = workers + 1): N threads are N - 1 workers
    if (threads > 1) mju_threadpool(data_, threads - 1);
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
    mj_deleteData(data_);  // also stops and frees the thread pool
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
            {"memory_mb", std::to_string(model_->narena >> 20)},
            {"iterations", std::to_string(model_->opt.iterations)},
            {"cone", model_->opt.cone == mjCONE_PYRAMIDAL ? "pyramidal" : "elliptic"},
            {"threads", std::to_string(threads_)},
            {"version", mj_versionString()}};
  }

  std::string Failure() const override {
    const std::string full = "mujoco: arena full (give more: --param memory_mb=N): ";
    if (data_->warning[mjWARN_CONTACTFULL].number > 0) return full + "contacts dropped";
    if (data_->warning[mjWARN_CNSTRFULL].number > 0) return full + "constraints dropped or Newton's factor left out";
    if (data_->warning[mjWARN_BADQACC].number > 0) return "nan: mujoco reset the state after a bad qacc";
    return "";
  }

 private:
  World mirror_;
  mjModel* model_;
  mjData* data_;
  std::string method_;
  int threads_;
  std::vector<int> index_;  // mirror index of each free body, in model order
};

// MuJoCo's default handler logs to MUJOCO_LOG.TXT in the working folder as
// well; a benchmark prints errors and warnings on stderr only, and an error
// (always fatal: the handler must not return) ends the process.
void LogToStderr(const mjLogMessage* message) {
  if (message->level < mjLOG_WARNING) return;
  const bool error = message->level == mjLOG_ERROR;
  std::fprintf(stderr, "mujoco %s: %s\n", error ? "error" : "warning", message->subject);
  if (error) std::exit(1);
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
  int arena_mb = DefaultArenaMb(static_cast<int>(world.bodies().size()));
  ParamReader reader(options.method.c_str(), options.params);
  reader.Int("iterations", 1, 100000, &iterations);
  reader.Int("memory_mb", 1, 1 << 20, &arena_mb);
  Status st = reader.Finish();
  if (st.ok()) st = CheckPeerShapes(world, "MuJoCo", kRefusesSurfaces);
  if (st.ok()) st = CheckPeerJoints(world, "MuJoCo", kRefusesJoints);
  if (!st.ok()) return st;

  mju_setLogHandler(LogToStderr);
  const std::string xml = ModelXml(world, arena_mb);
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  mj_addBufferVFS(&vfs, "scene.xml", xml.data(), static_cast<int>(xml.size()));
  char error[1000] = "";
  mjModel* model = mj_loadXML("scene.xml", &vfs, error, sizeof error);
  mj_deleteVFS(&vfs);
  if (!model) return Status::InvalidArgument(std::string("MuJoCo rejected the generated model: ") + error);
  model->opt.solver = solver;
  if (iterations > 0) model->opt.iterations = iterations;
  *out = std::make_unique<MujocoEngine>(world, model, options.method, options.threads);
  return Status::Ok();
}

}  // namespace
}  // namespace contactsim::bench

int main(int argc, char** argv) {
  contactsim::bench::RunnerInfo info;
  info.engine = "mujoco";
  info.description =
      std::string("contactsim-bench-mujoco: runs a contactsim scene file in MuJoCo ") + mj_versionString();
  info.default_method = "newton";
  info.methods = {"newton", "cg", "pgs"};
  info.threaded = true;
  info.factory = contactsim::bench::CreateMujocoEngine;
  return contactsim::bench::SceneBenchMain(argc, argv, info);
}
