#include "sensor_outputs.hpp"

#include <cmath>

namespace car_sim {

void ImuOut::visit(FieldVisitor& v) const {
  const double q[4] = {orientation.x(), orientation.y(), orientation.z(), orientation.w()};
  v.vector("orientation", q, 4);
  v.vector("angular_velocity", angular_velocity.data(), 3);
  v.vector("linear_acceleration", linear_acceleration.data(), 3);
}

std::vector<OutputPort> imu_ports(const PluginConfig& c, const std::string& robot, const Environment&) {
  OutputPort p = sensor_port(c, robot, "imu", sample_type<ImuSample>(), "topicName", c.text("frameName"), 1);
  const double variance = std::pow(c.number("gaussianNoise"), 2);
  p.orientation_covariance.fill(variance);
  p.angular_velocity_covariance.fill(variance);
  p.linear_acceleration_covariance.fill(variance);
  return std::vector<OutputPort>{p};
}

void RangeOut::visit(FieldVisitor& v) const {
  v.integer("radiation_type", radiation);
  v.number("field_of_view", field_of_view);
  v.number("min_range", min_range);
  v.number("max_range", max_range);
  v.number("range", range);
}

}  // namespace car_sim
