#include "camera.hpp"

namespace car_sim {

const PluginKind& camera_kind() {
  static const PluginKind k = camera_kind_record();
  return k;
}

}  // namespace car_sim
