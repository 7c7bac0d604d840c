// contactsim::Client: a C++ client of contactsim-server that speaks only the
// LCM types of docs/protocol.md (it never includes server code).
//
// Every command is published on <prefix>_BODY_CMD, _SCENE_CMD or _JOINT_CMD with
// this client's id and a fresh request id, and the call blocks until the
// matching reply_t arrives on <prefix>_REPLY or the reply timeout passes.
// Nothing throws across this API: failures come back as a CommandResult code.
//
// A background thread receives STATE, CONTACTS, STATUS and REPLY messages.
// Callbacks run on that thread, so they must return quickly and must not
// call the blocking commands of the same Client (whose replies that very
// thread would have to deliver).
//
// With an auth key (ClientOptions::auth_key_file) every message this client
// publishes is signed, and REPLY, STATE, CONTACTS and STATUS messages whose
// signature fails are dropped and counted (docs/protocol.md, "Authentication").
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include <contactsim/actuator_cmd_t.hpp>
#include <contactsim/body_cmd_t.hpp>
#include <contactsim/contacts_t.hpp>
#include <contactsim/input_t.hpp>
#include <contactsim/joint_cmd_t.hpp>
#include <contactsim/joint_state_t.hpp>
#include <contactsim/model_cmd_t.hpp>
#include <contactsim/model_info_t.hpp>
#include <contactsim/progress_t.hpp>
#include <contactsim/ray_cast_t.hpp>
#include <contactsim/ray_hits_t.hpp>
#include <contactsim/reply_t.hpp>
#include <contactsim/result.h>
#include <contactsim/scene_cmd_t.hpp>
#include <contactsim/sensor_cmd_t.hpp>
#include <contactsim/sensors_t.hpp>
#include <contactsim/signature.h>
#include <contactsim/state_t.hpp>
#include <contactsim/status_t.hpp>

namespace lcm {
class LCM;
class ReceiveBuffer;
}  // namespace lcm

namespace contactsim {

// The project default (docs/protocol.md): host-local multicast with an 8 MiB
// receive buffer so that large, fragmented STATE messages survive.
inline constexpr char kDefaultLcmUrl[] =
    "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608";

// "" -> $LCM_DEFAULT_URL when set, else kDefaultLcmUrl; anything else as is.
std::string ResolveLcmUrl(const std::string& url);

struct ClientOptions {
  std::string url;                    // "" -> ResolveLcmUrl("")
  std::string prefix = "CONTACTSIM";  // channel prefix <P>
  std::string client_id;              // "" -> "cpp-<pid>" (unique per Client)
  std::chrono::milliseconds reply_timeout{2000};
  // Key file for signed messages; nullopt -> $CONTACTSIM_AUTH_KEY_FILE, and
  // "" (or the variable unset) -> no signing. A key that cannot be loaded
  // leaves the client !good() with error() saying why.
  std::optional<std::string> auth_key_file;
  double auth_window_s = kDefaultAuthWindowSeconds;  // s, |seq - now| accepted
};

class ClientAuth;

enum class Mode : int8_t { kRealtime = 1, kFreeRun = 2, kLockstep = 3 };

// What the server does when a lockstep controller's input is late
// (docs/lockstep.md); kDefault: the server's configured policy.
enum class LatePolicy : int8_t { kDefault = 0, kWait = 1, kReuse = 2, kDrop = 3 };

// A lockstep input for one body, acting for one step. SI, world frame.
struct BodyWrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // N, at the centre of mass
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // N m
};
using BodyInputs = std::map<int64_t, BodyWrench>;  // body id -> wrench

// Actuator fields for a list of joints (docs/actuators.md, "Joint
// channels"): world joint ids, or a model (model_id > 0 with joint_ids
// empty: its joints with a coordinate, in the model's order). A field left
// empty is not sent (the joints keep their standing value); a field given
// has one value per joint. Standing settings on ACTUATOR_CMD
// (SetJointActuators), or one step's in a lockstep input (SendInput).
struct JointCommand {
  int64_t model_id = 0;
  std::vector<int64_t> joint_ids;
  std::vector<double> torque;           // N m or N
  std::vector<double> target_position;  // rad or m (acts while kp > 0)
  std::vector<double> target_velocity;  // rad/s or m/s (acts while kd > 0)
  std::vector<double> kp, kd;           // >= 0
  std::vector<double> effort_limit;     // > 0, inf: none
  std::vector<double> velocity_limit;   // > 0, inf: none
  bool empty() const { return model_id == 0 && joint_ids.empty(); }
};
// The wire form; an empty command is "no joints".
joint_command_t EncodeJointCommand(const JointCommand& command);

// Which bodies a body touches (docs/physics.md, "Collision filtering"), as
// Box2D's b2Filter: two bodies touch when (category_a & mask_b) and
// (category_b & mask_a) are nonzero, except that two bodies of one nonzero
// group always touch (group > 0) or never (group < 0).
struct CollisionFilter {
  uint32_t category = 1;         // the bits the body is
  uint32_t mask = 0xFFFFFFFFu;   // the bits it touches
  int32_t group = 0;
};

// Initial state and material of a new body. Units are SI, world frame.
struct BodyOptions {
  // m: the origin of the body's frame (a convex's points', a compound's
  // parts'), the centre of mass for a sphere, box or capsule
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::array<double, 4> orientation{1.0, 0.0, 0.0, 0.0};  // (w, x, y, z)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // m/s
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s
  std::optional<double> mass;      // kg; give at most one of mass, density
  std::optional<double> density;   // kg/m^3; neither: the server's 1000
  std::optional<double> restitution;  // [0, 1]; unset: the server default
  std::optional<double> friction;     // >= 0; unset: the server default
  bool fixed = false;                 // static body
  bool kinematic = false;             // infinite mass, moves with its velocity
  std::string name;                   // label in logs and snapshots
  // Explicit mass properties (a robot link's inertial), any shape but a
  // plane: the centre of mass (m, body frame) and the inertia about it (kg
  // m^2, body axes, symmetric positive definite; needs mass).
  std::optional<Eigen::Vector3d> center_of_mass;
  std::optional<Eigen::Matrix3d> inertia;
  std::optional<CollisionFilter> filter;  // unset: touches every body
};

// How a height map file becomes heights (AddHeightfieldFile).
struct HeightMapOptions {
  int rows = 0;          // a raw file's rows (along body y); a PNG: 0 or its height
  int cols = 0;          // a raw file's columns (along body x); a PNG: 0 or its width
  double scale = 1.0;    // m at the largest sample, 65535
  double offset = 0.0;   // m at sample 0
};

// One shape of a compound body (AddCompound), posed in the body's frame.
struct ShapePart {
  enum class Type : int8_t { kSphere = 1, kBox = 2, kCapsule = 4, kConvex = 5 };  // body_cmd_t codes
  Type type = Type::kSphere;
  double radius = 0.0;                                         // m, sphere and capsule
  Eigen::Vector3d half_extents = Eigen::Vector3d::Zero();      // m, box
  double half_length = 0.0;                                    // m, capsule, along the part's z
  std::vector<Eigen::Vector3d> points;                         // m, convex, part frame
  Eigen::Vector3d position = Eigen::Vector3d::Zero();          // m, body frame
  std::array<double, 4> orientation{1.0, 0.0, 0.0, 0.0};       // (w, x, y, z), part to body
};

// Joint kinds, as joint_cmd_t codes (docs/physics.md, "Joints").
enum class JointType : int8_t { kDistance = 1, kBall = 2, kHinge = 3, kFixed = 4, kPrismatic = 5 };

// The optional fields of a new joint. World frame, at the moment of creation.
struct JointOptions {
  std::optional<Eigen::Vector3d> axis;  // hinge and prismatic, required there
  std::optional<double> length;         // m, distance only; unset: the current distance
  // (lower, upper): hinge (rad) and prismatic (m, along the axis); one-sided stops
  std::optional<std::pair<double, double>> limits;
  std::optional<double> damping;   // N m s/rad (hinge) or N s/m (prismatic), >= 0; unset: 0
  std::optional<double> friction;  // N m (hinge) or N (prismatic), >= 0, Coulomb; unset: 0
  bool collide_connected = false;  // may the two bodies touch each other (default: never)
};

// How a robot model is placed (docs/models.md). The root link's frame in
// the world; SI.
struct ModelOptions {
  std::string name;                                       // unique; "": the file's
  Eigen::Vector3d position = Eigen::Vector3d::Zero();     // m
  std::array<double, 4> orientation{1.0, 0.0, 0.0, 0.0};  // (w, x, y, z)
  bool fixed_base = false;                                // the root link is static
  bool self_collide = false;  // the model's links collide (two joined by a joint never do)
  // each collision mesh: the convex hull of at most this many of its vertices
  // (>= 4); 0: the server's default (64); -1: every vertex (docs/models.md)
  int32_t max_hull_vertices = 0;
  int8_t format = model_cmd_t::FORMAT_AUTO;               // or FORMAT_URDF, FORMAT_SDF
};

// A loaded model: the file's link and joint names, in its order, and their
// ids in the world. BodyId of a link welded to its parent by a fixed joint
// is its parent's body; JointId of a fixed (merged) or floating joint is 0;
// both are -1 for a name the model does not have.
struct Model {
  int64_t id = 0;
  std::string name;
  std::vector<std::string> links, joints;
  std::vector<int64_t> link_bodies, joint_ids;

  int64_t BodyId(const std::string& link) const;
  int64_t JointId(const std::string& joint) const;
  static Model FromInfo(const model_entry_t& entry);
};

class Client {
 public:
  using StateCallback = std::function<void(const state_t&)>;
  using ContactsCallback = std::function<void(const contacts_t&)>;
  using StatusCallback = std::function<void(const status_t&)>;
  using ReplyCallback = std::function<void(const reply_t&)>;
  using ProgressCallback = std::function<void(const progress_t&)>;
  using SensorsCallback = std::function<void(const sensors_t&)>;
  using JointStateCallback = std::function<void(const joint_state_t&)>;
  using Clock = std::chrono::steady_clock;

  explicit Client(ClientOptions options = {});
  ~Client();
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  // False when LCM could not be opened (bad URL, no multicast route); every
  // command then returns ReplyCode::kTransport.
  bool good() const;
  // Why good() is false ("" when it is true).
  std::string error() const;
  const std::string& client_id() const { return options_.client_id; }
  const std::string& url() const { return options_.url; }
  const std::string& prefix() const { return options_.prefix; }
  std::string Channel(const std::string& suffix) const;  // "<P>_<suffix>"

  // --- signed messages (with an auth key) ---
  bool signs() const { return auth_ != nullptr; }
  // Server messages dropped because their signature, freshness or seq
  // failed, and the reason of the last one ("<channel>: <why>").
  uint64_t auth_failures() const;
  std::string last_auth_failure() const;

  // --- scene commands ---
  CommandResult Reset();
  CommandResult LoadScene(const std::string& path);  // on the server's host
  CommandResult SetGravity(const Eigen::Vector3d& gravity);  // m/s^2
  CommandResult SetTimestep(double dt);                      // s
  CommandResult SetContactMethod(
      const std::string& name,
      const std::map<std::string, std::string>& params = {});
  CommandResult Pause();
  CommandResult Resume();
  // Takes n steps and leaves the run paused. Returns after the reply AND once
  // a STATE with step >= reply.step has arrived (so LatestState() shows it).
  // Waits as long as the server reports progress (PROGRESS): kTimeout only
  // after reply_timeout without any. `progress` (on the receive thread) gets
  // each report. A PAUSE from any client stops the steps: FAILED_PRECONDITION
  // "step interrupted: cancelled by PAUSE ... after k of n steps".
  CommandResult Step(int32_t n = 1, ProgressCallback progress = {});
  CommandResult SetMode(Mode mode, double real_time_factor = 1.0);

  // --- snapshots (docs/snapshots.md) ---
  // Saves the world to the server's slot `name` / to a file on its host.
  CommandResult SaveSnapshot(const std::string& name);
  CommandResult SaveSnapshotToFile(const std::string& path);
  // Replaces the world by a snapshot; the run continues exactly as it did.
  CommandResult Restore(const std::string& name);
  CommandResult RestoreFromFile(const std::string& path);
  // Back to the state after `step` steps (nearest snapshot + journal replay).
  CommandResult Rewind(int64_t step);

  // --- lockstep (docs/lockstep.md; contactsim/controller.h runs a loop) ---
  // This client becomes a controller: in LOCKSTEP mode the server takes no
  // step before this client's input for it. late_timeout in s (0: the
  // server's) applies to kReuse and kDrop.
  CommandResult RegisterController(LatePolicy policy = LatePolicy::kDefault, double late_timeout = 0.0);
  CommandResult ReleaseController();
  // Publishes the input for `step` (the last STATE's step + 1); empty
  // inputs mean "no input". Returns at once with the request id (0 when
  // LCM failed): the STATE of `step` acknowledges it, a refusal comes as an
  // error reply (OnReply). Safe to call from an OnState callback.
  // `request_id` > 0 resends an input under its first id (the server
  // ignores a resend of the input it has just applied).
  int64_t SendInput(int64_t step, const BodyInputs& inputs, int64_t request_id = 0);
  // The same with joint commands acting for that step only.
  int64_t SendInput(int64_t step, const BodyInputs& inputs, const JointCommand& joints, int64_t request_id = 0);

  // --- joint actuators (docs/actuators.md, "Joint channels") ---
  // Sets the fields given of the joints' standing actuators; the whole
  // command is refused if any joint or value is. reply.ids: the joints.
  CommandResult SetJointActuators(const JointCommand& command);
  // Removes the actuators of the joints, or (ids empty) of the model's joints.
  CommandResult ClearJointActuators(const std::vector<int64_t>& joint_ids, int64_t model_id = 0);
  CommandResult Send(actuator_cmd_t command);

  // --- body commands; Add* return the new id ---
  Result<int64_t> AddSphere(double radius, const BodyOptions& options = {});
  Result<int64_t> AddBox(const Eigen::Vector3d& half_extents,
                         const BodyOptions& options = {});
  Result<int64_t> AddCapsule(double radius, double half_length,
                             const BodyOptions& options = {});
  Result<int64_t> AddConvex(const std::vector<Eigen::Vector3d>& points,
                            const BodyOptions& options = {});
  // One rigid body of 1 to 64 shapes (docs/physics.md, "Compound bodies and
  // mass properties"); options.position places the parts' frame.
  Result<int64_t> AddCompound(const std::vector<ShapePart>& parts,
                              const BodyOptions& options = {});
  // The plane {p : normal . p = offset}; always static. Only the material
  // and name of `options` are used.
  Result<int64_t> AddPlane(const Eigen::Vector3d& normal, double offset = 0.0,
                           const BodyOptions& options = {});
  // A static triangle mesh (docs/physics.md, "Triangle meshes and
  // heightfields"): vertices (m, body frame, times `scale`) and three
  // indices per triangle, counter-clockwise seen from the front; or a mesh
  // file (OBJ, STL, PLY, DAE, ...) the server reads. options.position and
  // orientation place the body frame; its material, name and filter are
  // used. Triangles of zero area are dropped; the reply says how many.
  Result<int64_t> AddMesh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<int32_t>& indices,
                          double scale = 1.0, const BodyOptions& options = {});
  Result<int64_t> AddMeshFile(const std::string& path, double scale = 1.0, const BodyOptions& options = {});
  // A static heightfield: `heights` row-major, rows along body y and
  // columns along body x, spacing_x and spacing_y apart (m), centred on
  // options.position.
  Result<int64_t> AddHeightfield(int rows, int cols, const std::vector<double>& heights, double spacing_x,
                                 double spacing_y, const BodyOptions& options = {});
  // A static heightfield from a height map file the server reads (a
  // relative path against its model paths): a 16-bit greyscale PNG (rows
  // and cols 0, or its size) or a raw file of rows x cols little-endian
  // uint16 samples. The file's first row is the grid's last (largest y),
  // and sample s is the height offset + scale s / 65535 (m).
  Result<int64_t> AddHeightfieldFile(const std::string& path, double spacing_x, double spacing_y,
                                     const HeightMapOptions& map = {}, const BodyOptions& options = {});
  CommandResult RemoveBody(int64_t id);
  CommandResult SetPose(int64_t id, const Eigen::Vector3d& position,
                        const std::array<double, 4>& orientation = {1, 0, 0, 0});
  CommandResult SetVelocity(int64_t id, const Eigen::Vector3d& velocity,
                            const Eigen::Vector3d& angular_velocity =
                                Eigen::Vector3d::Zero());
  // Force (N) and torque (N m) at the centre of mass for `duration` seconds
  // of simulated time (0: the next step only).
  CommandResult ApplyForce(int64_t id, const Eigen::Vector3d& force,
                           const Eigen::Vector3d& torque = Eigen::Vector3d::Zero(),
                           double duration = 0.0);
  // Impulse (N s) at `point` (world frame), or at the centre of mass.
  CommandResult ApplyImpulse(int64_t id, const Eigen::Vector3d& impulse,
                             const std::optional<Eigen::Vector3d>& point = {});
  CommandResult SetMass(int64_t id, double mass);        // kg
  CommandResult SetDensity(int64_t id, double density);  // kg/m^3
  CommandResult SetMaterial(int64_t id, std::optional<double> restitution,
                            std::optional<double> friction);
  // Replaces the body's collision filter; wakes it and what touches it.
  CommandResult SetFilter(int64_t id, const CollisionFilter& filter);

  // --- joint commands ---
  // Adds a joint between body_a and body_b (0: the world) at `anchor` (m,
  // world; distance: the point on body_b, body_a held at its centre of
  // mass); returns the new joint id.
  Result<int64_t> AddJoint(JointType type, int64_t body_a, int64_t body_b,
                           const Eigen::Vector3d& anchor,
                           const JointOptions& options = {});
  CommandResult RemoveJoint(int64_t id);

  // --- ray casts and sensors (docs/protocol.md, "Ray casts", "Sensors") ---
  // Casts one ray per origin (m, world) along the direction of the same
  // index, each up to its max distance (m; one value applies to all);
  // rays pass through the bodies in `ignore`. The value is the server's
  // answer from RAY_HITS, in the rays' order.
  Result<ray_hits_t> RayCast(const std::vector<Eigen::Vector3d>& origins,
                             const std::vector<Eigen::Vector3d>& directions,
                             const std::vector<double>& max_distances,
                             const std::vector<int64_t>& ignore = {});
  // A fan of rays from `body` (origin and directions in its frame), read
  // on SENSORS as the range reading called `name`.
  CommandResult AddRangeSensor(int64_t body, const std::string& name,
                               const std::vector<Eigen::Vector3d>& directions, double max_distance,
                               const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());
  // The contact wrench `body` receives each step, read on SENSORS.
  CommandResult AddContactSensor(int64_t body, const std::string& name);
  CommandResult RemoveSensor(const std::string& name);
  // --- robot models (docs/models.md) ---
  // Loads a URDF or SDF model: a file path on the server's host (resolved
  // against its model paths) or the file's text (it starts with '<').
  Result<Model> LoadModel(const std::string& path_or_text, const ModelOptions& options = {});
  CommandResult RemoveModel(int64_t id);
  // Every model in the world now (asks the server for MODEL_INFO).
  Result<std::vector<Model>> Models();

  // Raw commands: client_id and request_id are filled in here. For fields
  // the typed methods do not cover, and for tests of the server's checks.
  CommandResult Send(body_cmd_t command);
  // progress: called with each PROGRESS report of this command (STEP, REWIND).
  CommandResult Send(scene_cmd_t command, ProgressCallback progress = {});
  CommandResult Send(joint_cmd_t command);
  CommandResult Send(sensor_cmd_t command);
  CommandResult Send(model_cmd_t command);

  // --- subscriptions ---
  // Each returns an id for RemoveCallback. Callbacks run on the LCM thread,
  // before the message reaches LatestState() and waiting commands: when
  // Step() returns, OnState callbacks have seen its state.
  int OnState(StateCallback callback);
  int OnContacts(ContactsCallback callback);
  int OnStatus(StatusCallback callback);
  int OnReply(ReplyCallback callback);  // every reply, any client's
  int OnSensors(SensorsCallback callback);
  int OnJointState(JointStateCallback callback);
  void RemoveCallback(int id);

  std::optional<state_t> LatestState() const;
  std::optional<contacts_t> LatestContacts() const;
  std::optional<status_t> LatestStatus() const;
  std::optional<sensors_t> LatestSensors() const;
  // The latest joint state: the joints of the latest STATE, or the latest
  // JOINT_STATE when that is of the same step or newer, or STATE carries no
  // joints. JOINT_STATE
  // goes out just before the STATE of the same step, outside lockstep by
  // default (the server's joint_state option; docs/actuators.md).
  std::optional<joint_state_t> LatestJointState() const;
  // STATE's joint block as a joint_state_t, named from the latest
  // MODEL_INFO (a joint it does not name: its id in decimal, as JOINT_STATE
  // names a joint of no model); empty when the world has no joints.
  joint_state_t JointStateOf(const state_t& state) const;
  // The first joint state (LatestJointState, now or later) for which
  // `predicate` holds; nullopt after `timeout`. An actuator_cmd_t STATE
  // asks the server for a JOINT_STATE now.
  std::optional<joint_state_t> WaitForJointState(const std::function<bool(const joint_state_t&)>& predicate,
                                                 std::chrono::milliseconds timeout);

  // True once a STATUS has arrived (the server publishes one at start and
  // then at status_rate_hz), false after `timeout`.
  bool WaitForServer(std::chrono::milliseconds timeout);
  // The first state (the latest one, or one arriving later) for which
  // `predicate` holds; nullopt after `timeout`.
  std::optional<state_t> WaitForState(
      const std::function<bool(const state_t&)>& predicate,
      std::chrono::milliseconds timeout);

 private:
  struct Callbacks;

  CommandResult Publish(const std::string& channel, int64_t request_id,
                        const void* data, int size);
  CommandResult AddBody(body_cmd_t command, const BodyOptions& options);
  body_cmd_t NewBodyCommand(int8_t op, int64_t body_id) const;
  scene_cmd_t NewSceneCommand(int8_t op) const;
  int64_t NextRequestId();
  bool PublishRaw(const std::string& channel, const void* data, int size);  // no reply awaited
  bool Transmit(const std::string& channel, const void* data, int size);    // signs with a key
  // Decodes a received message after checking its signature (with a key)
  // or stripping a trailer (without); false drops it.
  template <typename Msg>
  bool Unwrap(const lcm::ReceiveBuffer* rbuf, const std::string& channel, Msg* msg);

  void Run();
  void HandleReply(const lcm::ReceiveBuffer*, const std::string&,
                   const reply_t* reply);
  void HandleState(const lcm::ReceiveBuffer*, const std::string&,
                   state_t* state);
  void HandleContacts(const lcm::ReceiveBuffer*, const std::string&,
                      const contacts_t* contacts);
  void HandleStatus(const lcm::ReceiveBuffer*, const std::string&,
                    const status_t* status);
  static void OnReply(const lcm::ReceiveBuffer*, const std::string&, Client*);
  static void OnState(const lcm::ReceiveBuffer*, const std::string&, Client*);
  static void OnContacts(const lcm::ReceiveBuffer*, const std::string&, Client*);
  static void OnStatus(const lcm::ReceiveBuffer*, const std::string&, Client*);
  static void OnProgress(const lcm::ReceiveBuffer*, const std::string&, Client*);
  static void OnRayHits(const lcm::ReceiveBuffer*, const std::string&, Client*);
  static void OnSensors(const lcm::ReceiveBuffer*, const std::string&, Client*);
  void SubscribeSensors(int queue_capacity);
  static void OnJointState(const lcm::ReceiveBuffer*, const std::string&, Client*);
  static void OnModelInfo(const lcm::ReceiveBuffer*, const std::string&, Client*);
  // LatestJointState and JointStateOf with mutex_ held
  std::optional<joint_state_t> LatestJointStateLocked() const;
  joint_state_t JointStateOfLocked(const state_t& state) const;
  // The latest MODEL_INFO received after the `after`-th, within the reply timeout.
  std::optional<model_info_t> WaitForModelInfo(uint64_t after, const std::function<bool(const model_info_t&)>& predicate);
  void HandleProgress(const progress_t* progress);

  ClientOptions options_;
  std::string error_;               // why the client is not usable (an auth key problem)
  std::unique_ptr<ClientAuth> auth_;  // null: no signing
  std::unique_ptr<lcm::LCM> lcm_;

  mutable std::mutex mutex_;  // guards everything below
  std::condition_variable changed_;  // a reply, state or status arrived
  int64_t last_request_id_ = 0;
  std::map<int64_t, std::optional<reply_t>> pending_;  // request id -> reply
  // request id -> the last sign of the server working on it (sent, or PROGRESS)
  std::map<int64_t, std::chrono::steady_clock::time_point> heard_;
  std::map<int64_t, ProgressCallback> progress_callbacks_;  // request id -> Step's callback
  int progress_in_flight_ = 0;  // progress callbacks running now
  std::optional<state_t> latest_state_;
  uint64_t states_received_ = 0;  // lets Step ignore states older than its command
  std::optional<contacts_t> latest_contacts_;
  std::optional<status_t> latest_status_;
  std::optional<sensors_t> latest_sensors_;
  std::optional<joint_state_t> latest_joint_state_;
  std::map<int64_t, ray_hits_t> ray_hits_;  // request id -> answer, until RayCast takes it
  std::optional<model_info_t> latest_model_info_;
  uint64_t model_infos_received_ = 0;
  std::unique_ptr<Callbacks> callbacks_;
  std::atomic<bool> running_{true};
  std::thread thread_;  // last: starts after every member is ready
};

}  // namespace contactsim
