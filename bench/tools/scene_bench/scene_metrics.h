// The physics a benchmark run reports, computed from the engine's state
// after every step by the same code for every engine (the World mirror):
//  * max penetration: deepest contact over all steps, found by contactsim's
//    own collision detector on the engine's poses (margin 0), so engines are
//    judged by one ruler rather than by their own detectors;
//  * min distance: the smallest signed distance between two bodies over all
//    steps (negative: the deepest penetration), from contacts found within
//    kGapMargin, so a method that keeps bodies apart (barrier) shows its
//    gap; none when no two bodies ever came within kGapMargin;
//  * fell through: how many dynamic bodies had their centre below a static
//    triangle mesh or heightfield at some step (below the point of the
//    surface straight above or under it, found by a ray cast down from
//    above the surface); none when the scene has no such surface;
//  * final kinetic energy: sum of m v^2 / 2 + w . L / 2 of dynamic bodies;
//  * top displacement: |x - x0| of the body named "top";
//  * rebound height: the first apex of the lowest point of the body named
//    "ball" above the first plane (its signed distance to the plane), i.e.
//    the highest sample between the first bounce (normal velocity turning
//    from < 0 to > 0) and the normal velocity turning <= 0 again;
//  * health: a non-finite state is "nan"; a dynamic body farther than
//    kEscapeDistance from its start or faster than kEscapeSpeed is
//    "exploded" (no scene here moves a body that far or that fast: the
//    pyramid's top box falling its full 19.5 m reaches 20 m/s).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "service/collision/collision_detector.h"
#include "service/physics/world.h"

namespace contactsim::bench {

constexpr double kEscapeDistance = 50.0;  // m
constexpr double kEscapeSpeed = 50.0;     // m/s
constexpr double kGapMargin = 0.01;       // m: how far apart the min distance looks

// Follows one run (one object per run). Start() with the initial world, then Check() after every
// step (cheap: finiteness and bounds), and Observe() after the steps whose
// physics is measured (runs the collision detector).
class SceneMetrics {
 public:
  void Start(const World& world);
  // Empty when healthy; otherwise "nan" or "exploded", with the body named.
  std::string Check(const World& world) const;
  void Observe(const World& world);

  double max_penetration() const { return max_penetration_; }
  std::optional<double> min_distance() const { return min_distance_; }
  std::optional<int> fell_through() const;
  double final_kinetic_energy() const { return final_kinetic_energy_; }
  std::optional<double> top_displacement() const { return top_displacement_; }
  std::optional<double> rebound_height() const { return rebound_height_; }

 private:
  // Marks the dynamic bodies whose centre is below a surface now.
  void FindFallenBodies(const World& world);

  std::vector<Vec3> start_;
  std::vector<int> surfaces_;  // the static meshes and heightfields
  std::vector<bool> fell_;     // per body: was below a surface at some step
  int top_ = -1, ball_ = -1, plane_ = -1;
  CollisionDetector detector_;
  ContactSet contacts_;
  double max_penetration_ = 0.0;
  std::optional<double> min_distance_;
  double final_kinetic_energy_ = 0.0;
  std::optional<double> top_displacement_;
  std::optional<double> rebound_height_;
  // rebound: 0 before the first fall, 1 falling, 2 rising, 3 apex found
  int bounce_phase_ = 0;
  double apex_ = 0.0;
};

}  // namespace contactsim::bench
