// libFuzzer target: an SDF world file's text (load_world_string: sdformat, includes, <state>), simulated and stepped
// as sim_node would. Rule: fuzz_common.hpp.
#include <cstdint>
#include <string>

#include "car_sim/description.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  car_fuzz::run([&] {
    car_sim::World w(car_sim::load_world_string(xml, "fuzz.world"));
    car_fuzz::step_and_check(w);
  });
  return 0;
}
