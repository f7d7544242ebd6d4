// gazebo_plugins' GazeboRos::resolveTF (Noetic tf's tf::resolve) as the drive adapters apply it to their frames.
// Expected names worked out from tf::resolve's three cases (docs/COMPAT-spawn.md rule 4).
#include <gtest/gtest.h>

#include "frames.hpp"

using car_ros::resolve_tf;

TEST(ResolveTf, NoPrefixKeepsTheNameAsWritten) { EXPECT_EQ(resolve_tf("", "odom"), "odom"); }

TEST(ResolveTf, PrefixGoesInFrontWithASlash) { EXPECT_EQ(resolve_tf("robot1", "base_footprint"), "robot1/base_footprint"); }

TEST(ResolveTf, PrefixLosesItsLeadingSlash) { EXPECT_EQ(resolve_tf("/robot1", "odom"), "robot1/odom"); }

TEST(ResolveTf, AbsoluteNameTakesNoPrefixAndLosesOneSlash) { EXPECT_EQ(resolve_tf("robot1", "/map"), "map"); }
