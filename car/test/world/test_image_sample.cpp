// The camera samples' rules in the core (ports.hpp): a depth in millimetres as openni_kinect's 16UC1 depth image
// carries it, and which pixels of the organized cloud have a point. Values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "car_sim/ports.hpp"

using namespace car_sim;

// openni_kinect's `dest_uint16 = depth * 1000.0`: the float times 1000.0 in double, truncated.
TEST(ImageSampleDepth, MetresToTruncatedMillimetres) {
  EXPECT_EQ(depth_mm(1.5f), 1500);
  EXPECT_EQ(depth_mm(2.0004f), 2000);  // 2000.4 mm
  EXPECT_EQ(depth_mm(2.0006f), 2000);  // 2000.6 mm
  EXPECT_EQ(depth_mm(0.7f), 699);      // the float 0.699999988 m: 699.99998 mm
  EXPECT_EQ(depth_mm(0.0006f), 0);
  EXPECT_EQ(depth_mm(65.535f), 65535);  // the largest 16-bit value (65535.0037 mm)
  EXPECT_EQ(depth_mm(100.0f), 65535);   // beyond it (past every cutoff)
}

TEST(ImageSampleDepth, NoDepthIsZero) {
  EXPECT_EQ(depth_mm(std::nanf("")), 0);
  EXPECT_EQ(depth_mm(INFINITY), 0);
}

TEST(ImageSampleCloud, APointHasADepth) {
  const float near[3] = {0.1f, -0.2f, 3.0f};
  const float none[3] = {NAN, NAN, NAN};
  const float no_depth[3] = {0.1f, -0.2f, NAN};
  EXPECT_TRUE(has_point(near));
  EXPECT_FALSE(has_point(none));
  EXPECT_FALSE(has_point(no_depth));
}
