// The table of sample types (car_sim::Sample, ports.hpp) and how an output's samples reach its ports
// (SampleList::find): a sample for every port of its type, one named for a port, a camera's frames, and the types
// a sample serves by derivation. Values are the ones the test itself lists.
#include <gtest/gtest.h>

#include "car_sim/plugin.hpp"
#include "hector_imu/hector_imu.hpp"
#include "multicamera/multicamera.hpp"

using namespace car_sim;

namespace {

ImuSample imu(double wz) {
  ImuSample s;
  s.angular_velocity = Eigen::Vector3d(0, 0, wz);
  return s;
}

double wz(const Sample& s) { return std::get<ImuSample>(s).angular_velocity.z(); }

}  // namespace

// A sample held by pointer and one held by value name different alternatives; each type has its own index.
TEST(SampleTable, EachSampleTypeHasItsOwnIndex) {
  EXPECT_TRUE(std::holds_alternative<const LaserScanSample*>(
      Sample(std::in_place_index<sample_type<LaserScanSample>().index>, nullptr)));
  EXPECT_TRUE(std::holds_alternative<ImuSample>(Sample(std::in_place_index<sample_type<ImuSample>().index>)));
  EXPECT_NE(sample_type<Vector3Sample>(), sample_type<MagneticFieldSample>());
  EXPECT_NE(sample_type<ImageSample>(), sample_type<CameraInfoSample>());
}

// One unnamed sample: every port of its type takes it, whatever the port's name.
TEST(SampleList, AnUnnamedSampleServesEveryPortOfItsType) {
  SampleList list;
  list.add(imu(0.5));
  EXPECT_EQ(wz(list.find(sample_type<ImuSample>(), "imu", 0)), 0.5);
  EXPECT_EQ(wz(list.find(sample_type<ImuSample>(), "other", 0)), 0.5);
}

// hector_imu's two Imu ports: "bias" takes the sample named for it, "imu" the unnamed one, in either order of adding.
TEST(SampleList, ANamedSampleGoesToItsPortOnly) {
  for (const bool named_first : {false, true}) {
    SampleList list;
    if (named_first) list.add(imu(2.0), "bias");
    list.add(imu(1.0));
    if (!named_first) list.add(imu(2.0), "bias");
    EXPECT_EQ(wz(list.find(sample_type<ImuSample>(), "bias", 0)), 2.0) << named_first;
    EXPECT_EQ(wz(list.find(sample_type<ImuSample>(), "imu", 0)), 1.0) << named_first;
  }
}

// A port whose type nobody listed gets std::monostate (the bridge then sends nothing).
TEST(SampleList, NoSampleOfThePortsTypeIsMonostate) {
  SampleList list;
  list.add(imu(1.0));
  EXPECT_EQ(list.find(sample_type<RangeSample>(), "range", 0).index(), 0u);
}

// A sample the output holds goes by pointer: the port gets the output's own object, not a copy.
TEST(SampleList, AHeldSampleIsHandedOverByPointer) {
  LaserScanSample scan;
  scan.ranges = {1.0f, 2.0f};
  SampleList list;
  list.add(&scan);
  EXPECT_EQ(std::get<const LaserScanSample*>(list.find(sample_type<LaserScanSample>(), "scan", 0)), &scan);
}

// A camera frame's ImageSample serves its CameraInfo, DepthImage and DepthCloud ports, made into their types with
// the frame's fields (here width 8 and the depth array's address).
TEST(SampleList, AFrameServesTheTypesDerivedFromImageSample) {
  float depth[1] = {1.0f};
  ImageSample frame;
  frame.width = 8;
  frame.depth = depth;
  SampleList list;
  list.add(frame);
  const Sample info = list.find(sample_type<CameraInfoSample>(), "camera_info", 0);
  ASSERT_TRUE(std::holds_alternative<CameraInfoSample>(info));
  EXPECT_EQ(std::get<CameraInfoSample>(info).width, 8);
  const Sample d = list.find(sample_type<DepthImageSample>(), "depth", 0);
  ASSERT_TRUE(std::holds_alternative<DepthImageSample>(d));
  EXPECT_EQ(std::get<DepthImageSample>(d).depth, depth);
}

// The derivation serves one way: a CameraInfoSample listed serves no Image port.
TEST(SampleList, ABaseTypeIsNotServedByADerivedOne) {
  SampleList list;
  list.add(CameraInfoSample{});
  EXPECT_EQ(list.find(sample_type<ImageSample>(), "image", 0).index(), 0u);
}

// A multicamera lists one frame per side: a port reads the frame its settings name; a frame it lacks is none.
TEST(SampleList, APortReadsTheFrameItNames) {
  MultiCameraOut out;
  out.frames.resize(2);
  out.frames[0].width = 4;
  out.frames[1].width = 6;
  EXPECT_EQ(out.sample_of<ImageSample>({}, 0)->width, 4);
  EXPECT_EQ(out.sample_of<ImageSample>({}, 1)->width, 6);
  EXPECT_FALSE(out.sample_of<ImageSample>({}, 2));
}

// hector_imu's output: its "bias" port reads the biases (rate_bias as the angular velocity), its other port the
// measurement.
TEST(SampleList, HectorImuBiasPortReadsTheBiases) {
  HectorImuOut out;
  out.angular_velocity = Eigen::Vector3d(0, 0, 0.25);
  out.rate_bias = Eigen::Vector3d(0, 0, 0.125);
  EXPECT_EQ(out.sample_of<ImuSample>("bias")->angular_velocity.z(), 0.125);
  EXPECT_EQ(out.sample_of<ImuSample>("imu")->angular_velocity.z(), 0.25);
}
