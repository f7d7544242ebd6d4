// What every fuzz target checks (docs/RELIABILITY.md): an input either loads, or is refused with a LoadError whose
// what() is "FILE[:LINE]: ELEMENT: REASON". A loaded world is stepped and its state must stay finite, or the world
// must stop itself with a SimulationError (World::step's guard, "... is not finite; the world stops here").
// Anything else aborts, which libFuzzer records as a crash: another exception type, a malformed message, NaN or
// inf in a pose, twist or joint state. Hangs and memory are libFuzzer's (-timeout=1 -rss_limit_mb=2048).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <typeinfo>

#include "car_sim/description.hpp"
#include "car_sim/diagnostics.hpp"
#include "car_sim/world.hpp"

namespace car_fuzz {

[[noreturn]] inline void broke(const std::string& why) {
  std::fprintf(stderr, "car_fuzz: RULE BROKEN: %s\n", why.c_str());
  std::fflush(stderr);
  std::abort();
}

// "FILE[:LINE]: ELEMENT: REASON": a source and a reason, never empty; the element is left out only for what is
// wrong with the document as a whole ("FILE:LINE: malformed XML: ...", "FILE: root element is not <robot>..."), as
// LoadError formats it.
inline void check_refusal(const car_sim::LoadError& e) {
  const std::string what = e.what();
  if (e.file().empty() || e.reason().empty()) broke("LoadError without file or reason: '" + what + "'");
  const std::string want = e.file() + (e.line() > 0 ? ":" + std::to_string(e.line()) : "") +
                           (e.element().empty() ? "" : ": " + e.element()) + ": " + e.reason();
  if (what != want) broke("LoadError reads '" + what + "', not FILE[:LINE]: ELEMENT: REASON");
  if (e.line() < 0) broke("LoadError with a negative line: '" + what + "'");
}

// Gazebo's empty world (ground plane, sun), parsed once: sdformat reads its schema on every parse, which is not
// what the targets test.
inline const car_sim::WorldDescription& empty() {
  static const car_sim::WorldDescription w = car_sim::empty_world();
  return w;
}

inline bool finite(const car_sim::ModelState& s) {
  return s.pose.matrix().allFinite() && s.linear.allFinite() && s.angular.allFinite();
}

// Steps a loaded world: 1000 steps, fewer for big worlds so that one input stays well under libFuzzer's 1 s
// (about 20 000 model-steps; a 1000-model world still gets 20 steps). Returns true when the state stayed finite,
// false when the world stopped itself.
inline bool step_and_check(car_sim::World& w, uint64_t most = 1000) {
  // tools/fuzz.sh times a timeout's loading alone with CAR_FUZZ_NO_STEP=1 (the rule's 1 s is the loader's)
  static const bool no_step = std::getenv("CAR_FUZZ_NO_STEP") != nullptr;
  if (no_step) return false;
  const auto names = w.model_names();
  const std::size_t models = names.empty() ? 1 : names.size();
  const uint64_t steps = std::max<uint64_t>(20, std::min<uint64_t>(most, 20000 / models));
  try {
    w.step(steps);
  } catch (const car_sim::SimulationError& e) {
    const std::string what = e.what();
    if (what.find("not finite") == std::string::npos) broke("SimulationError without its reason: " + what);
    return false;  // the guard stopped the world: a refusal with a message
  }
  for (const auto& n : names)
    if (!finite(w.model_state(n))) broke("model '" + n + "' is not finite after " + std::to_string(steps) + " steps");
  for (const auto& r : w.robot_names())
    for (const auto& j : w.joint_states(r))
      if (!std::isfinite(j.position) || !std::isfinite(j.velocity))
        broke("joint '" + r + "/" + j.name + "' is not finite after " + std::to_string(steps) + " steps");
  return true;
}

// Runs `load` (a loader call and whatever it builds); a LoadError must be well formed, and nothing else may escape.
template <class F>
void run(F&& load) {
  try {
    load();
  } catch (const car_sim::LoadError& e) {
    check_refusal(e);
  } catch (const std::exception& e) {
    broke(std::string("escaped ") + typeid(e).name() + ": " + e.what());
  }
}

}  // namespace car_fuzz

// libFuzzer calls this once before the first input: what every process pays once (sdformat's first parse, the
// shared libraries' lazy binding, the empty world) is not counted in the first input's 1 s.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  car_sim::World w(car_fuzz::empty());
  w.step(1);
  try {
    car_sim::load_world_string("<sdf version='1.6'><world name='w'><model name='m'><link name='l'/></model></world></sdf>",
                               "warm-up.world");
  } catch (const std::exception&) {
  }
  return 0;
}
