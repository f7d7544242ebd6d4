// libFuzzer target: an SDF world file's text through world_tool flatten (flatten_world_file: includes resolved and
// inlined, nested models hoisted, <state> applied). Rule: fuzz_common.hpp; what flatten writes must be an SDF
// document again (one <sdf> root with one <world>), since world_tool's users load it.
#include <tinyxml2.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "car_sim/description.hpp"
#include "fuzz_common.hpp"

namespace {
// flatten reads a file (includes resolve against its folder): one per process, rewritten for each input and
// removed when the process exits normally (a crash leaves it, with the input that crashed)
struct ScratchFile {
  const std::string path = "/tmp/car-fuzz-flatten-" + std::to_string(getpid()) + ".world";
  ~ScratchFile() { std::remove(path.c_str()); }
};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const ScratchFile scratch;
  const std::string& path = scratch.path;
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  car_fuzz::run([&] {
    const std::string flat = car_sim::flatten_world_file(path);
    tinyxml2::XMLDocument doc;
    if (doc.Parse(flat.c_str(), flat.size()) != tinyxml2::XML_SUCCESS) car_fuzz::broke("flatten wrote malformed XML");
    const tinyxml2::XMLElement* root = doc.RootElement();
    if (!root || std::string(root->Name()) != "sdf" || !root->FirstChildElement("world"))
      car_fuzz::broke("flatten wrote no <sdf><world>");
  });
  return 0;
}
