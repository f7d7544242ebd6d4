// gpu_ray with libgazebo_ros_gpu_laser.so: the laser kind on the CPU ray kernel, the same scan as ray.
#include <gtest/gtest.h>

#include <cstring>

#include "../range/ray_world.hpp"
#include "laser/laser.hpp"
#include "seed_car.hpp"

using namespace car_sim;
using namespace car_sim::test_support;

namespace {

LaserScanOut scan_of(const std::string& xml) {
  World w(load_world_file(std::string(CAR_SOURCE_DIR) + "/worlds/box_house.world"));
  w.spawn(load_urdf_string(xml, "car"), "mycar", at(0.5, -0.5, 0.3));
  w.set_sensor_active("mycar", "gazebo_rplidar", true);
  w.step(200);
  const auto scans = w.take_outputs<LaserScanOut>();
  EXPECT_FALSE(scans.empty());
  return scans.back();
}

}  // namespace

// The seed car's lidar as a gpu_ray sensor with the GPU plug-in file: kind "laser", and bit for bit the ray
// sensor's scan (test/plugins/laser checks that scan against the world's geometry).
TEST(GpuLaser, GpuRaySensorIsTheLaserKindAndScansTheSame) {
  const std::string ray = car_xml(false);
  std::string gpu = ray;
  gpu.replace(gpu.find("type=\"ray\""), 10, "type=\"gpu_ray\"");
  gpu.replace(gpu.find("libgazebo_ros_laser.so"), 22, "libgazebo_ros_gpu_laser.so");
  const ModelConfig cfg = resolve_plugins(load_urdf_string(gpu, "car"));
  bool found = false;
  for (const auto& p : cfg.plugins)
    if (p.name == "gazebo_rplidar") {
      found = true;
      EXPECT_EQ(p.kind, "laser");
      EXPECT_EQ(p.sensor_type, "gpu_ray");
      EXPECT_EQ(p.filename, "libgazebo_ros_gpu_laser.so");
    }
  EXPECT_TRUE(found);
  const LaserScanOut a = scan_of(ray), b = scan_of(gpu);
  ASSERT_EQ(a.ranges.size(), 360u);
  ASSERT_EQ(a.ranges.size(), b.ranges.size());
  EXPECT_EQ(0, std::memcmp(a.ranges.data(), b.ranges.data(), a.ranges.size() * sizeof(float)));
}

// RayPlugin::Load throws on a GpuRaySensor: the model loads without the plug-in.
TEST(GpuLaser, LaserFileOnAGpuRaySensorDoesNotLoad) {
  const std::string plugin = "<plugin name='p' filename='libgazebo_ros_laser.so'/>";
  EXPECT_EQ(not_loaded_on("gpu_ray", plugin),
            "libgazebo_ros_laser.so needs a sensor of type ray, not 'gpu_ray'; the plug-in is not loaded");
  // and absent, not only reported: nothing resolved, so the world runs no laser kind for it; the same element on a
  // ray sensor loads (the check is not empty for another reason)
  EXPECT_EQ(loaded_kinds_on("gpu_ray", plugin), std::vector<std::string>{});
  EXPECT_EQ(loaded_kinds_on("ray", plugin), std::vector<std::string>{"laser"});
}

// GpuRayPlugin::Load throws on a RaySensor: the model loads without the plug-in.
TEST(GpuLaser, GpuFileOnARaySensorDoesNotLoad) {
  const std::string plugin = "<plugin name='p' filename='libgazebo_ros_gpu_laser.so'/>";
  EXPECT_EQ(not_loaded_on("ray", plugin),
            "libgazebo_ros_gpu_laser.so needs a sensor of type gpu_ray, not 'ray'; the plug-in is not loaded");
  // and absent, not only reported: nothing resolved, so the world runs no laser kind for it; the same element on a
  // gpu_ray sensor loads (the check is not empty for another reason)
  EXPECT_EQ(loaded_kinds_on("ray", plugin), std::vector<std::string>{});
  EXPECT_EQ(loaded_kinds_on("gpu_ray", plugin), std::vector<std::string>{"laser"});
}
