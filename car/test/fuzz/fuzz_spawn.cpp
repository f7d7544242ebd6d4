// libFuzzer target: the gazebo_msgs/SpawnModel request path of sim_node (SimNode::spawn in src/ros/services.cpp)
// without ROS, then a SetModelState request on what was spawned. The input is the request as text:
//   line 1: model_name|robot_namespace|reference_frame|x y z qx qy qz qw        (initial_pose)
//   line 2: x y z qx qy qz qw vx vy vz wx wy wz                                  (set_model_state)
//   rest:   model_xml (URDF, or an <sdf> document as spawn_model -sdf sends)
// The node answers std::invalid_argument (a taken name, a non-finite state) and LoadError as a failed request, so
// both are refusals here. Rule otherwise as fuzz_common.hpp.
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "car_sim/description.hpp"
#include "car_sim/model.hpp"
#include "car_sim/sdf_model.hpp"
#include "fuzz_common.hpp"

namespace {

std::vector<double> numbers(const std::string& s, std::size_t n) {
  std::istringstream in(s);
  std::vector<double> v(n, 0.0);
  for (auto& x : v)
    if (!(in >> x)) break;
  return v;
}

// as from_pose (src/ros/conversions.hpp): an all-zero quaternion means no rotation, any other is normalised
Eigen::Isometry3d pose_of(const std::vector<double>& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  Eigen::Quaterniond q(p[6], p[3], p[4], p[5]);
  if (q.norm() < 1e-12) q = Eigen::Quaterniond::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  return T;
}

std::string line(std::string* rest) {
  const auto nl = rest->find('\n');
  std::string l = rest->substr(0, nl);
  *rest = nl == std::string::npos ? "" : rest->substr(nl + 1);
  return l;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string rest(reinterpret_cast<const char*>(data), size);
  std::string head = line(&rest);
  const std::string set = line(&rest);
  std::vector<std::string> f;
  std::istringstream hs(head);
  for (std::string x; std::getline(hs, x, '|');) f.push_back(x);
  f.resize(4);
  const std::string& name = f[0];
  const std::string& ns = f[1];
  // SimNode::spawn: only '' and 'world' are supported reference frames
  if (!(f[2].empty() || f[2] == "world")) return 0;
  car_sim::World w(car_fuzz::empty());
  car_fuzz::run([&] {
    try {
      const bool is_sdf = car_sim::is_sdf_document(rest);
      if (is_sdf)
        w.spawn_sdf(car_sim::load_sdf_model_string(rest, name), name, pose_of(numbers(f[3], 7)), ns);
      else
        w.spawn(car_sim::load_urdf_string(rest, name), name, pose_of(numbers(f[3], 7)), ns);
    } catch (const std::invalid_argument&) {
      return;  // the node's "SpawnModel: failure - ..." for a name it cannot take
    }
    const auto s = numbers(set, 13);
    car_sim::ModelState st;
    st.pose = pose_of(s);
    st.linear = Eigen::Vector3d(s[7], s[8], s[9]);
    st.angular = Eigen::Vector3d(s[10], s[11], s[12]);
    try {
      w.set_model_state(name, st);
    } catch (const std::invalid_argument&) {
      // the node's SetModelState failure (a non-finite state)
    }
    car_fuzz::step_and_check(w);
  });
  return 0;
}
