// control_toolbox::Pid's and PidGainsSetter's ROS side, as control_toolbox 1.19.0: init() reads the gains from the
// parameter server (pid_ros.test sets them), refuses a missing p with upstream's message, publishes
// control_msgs/PidState on "state" with publish_state, and serves dynamic_reconfigure in its namespace;
// PidGainsSetter's set_gains sets every added Pid. Run by rostest: the node handles need a ROS master.
#include <control_toolbox/SetPidGains.h>
#include <control_toolbox/pid.h>
#include <control_toolbox/pid_gains_setter.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tinyxml.h>

#include <string>
#include <vector>

using control_toolbox::Pid;

namespace {

std::vector<double> gains(Pid& pid) {
  const Pid::Gains g = pid.getGains();
  return {g.p_gain_, g.i_gain_, g.d_gain_, g.i_max_, g.i_min_};
}

// [s] of wall time for a ROS connection or a message: generous, and a timeout fails naming what it waited for
constexpr double kWait = 30.0;

}  // namespace

TEST(PidRos, InitReadsTheGainsAndMakesTheClampSymmetric) {
  Pid pid;
  ASSERT_TRUE(pid.init(ros::NodeHandle("pid_a")));
  // i_clamp -3 gives [-3, 3]
  EXPECT_EQ((std::vector<double>{2.0, 0.5, 0.1, 3.0, -3.0}), gains(pid));
  EXPECT_FALSE(pid.getGains().antiwindup_);
}

TEST(PidRos, ClampMinAndMaxOverrideIClampWithTheirSignsForced) {
  Pid pid;
  ASSERT_TRUE(pid.initParam("pid_b"));
  // i_clamp_min 5 -> -5, i_clamp_max -4 -> 4; i and d default to 0
  EXPECT_EQ((std::vector<double>{1.0, 0.0, 0.0, 4.0, -5.0}), gains(pid));
}

TEST(PidRos, InitWithoutPFailsWithUpstreamsMessage) {
  Pid pid;
  testing::internal::CaptureStderr();
  const bool ok = pid.init(ros::NodeHandle("pid_none"));
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_FALSE(ok);
  EXPECT_NE(std::string::npos, err.find("No p gain specified for pid.  Namespace: /pid_none")) << err;
}

TEST(PidRos, QuietInitFailsWithoutAMessage) {
  Pid pid;
  testing::internal::CaptureStderr();
  const bool ok = pid.init(ros::NodeHandle("pid_none"), true);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_FALSE(ok);
  EXPECT_EQ(std::string::npos, err.find("No p gain")) << err;
}

TEST(PidRos, PublishStateSendsEachCommandsTerms) {
  Pid pid;
  ASSERT_TRUE(pid.init(ros::NodeHandle("pid_state")));
  ros::NodeHandle nh;
  control_msgs::PidState got;
  bool have = false;
  ros::Subscriber sub = nh.subscribe<control_msgs::PidState>(
      "/pid_state/state", 1, [&](const control_msgs::PidState::ConstPtr& m) { got = *m, have = true; });
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(kWait);
  while (sub.getNumPublishers() == 0 && ros::WallTime::now() < until) ros::WallDuration(0.01).sleep();
  ASSERT_GT(sub.getNumPublishers(), 0u) << "no publisher on /pid_state/state within " << kWait << " s";
  // p 2 * error 0.5
  EXPECT_DOUBLE_EQ(1.0, pid.computeCommand(0.5, 0.0, ros::Duration(0.1)));
  while (!have && ros::WallTime::now() < until) ros::WallDuration(0.01).sleep();
  ASSERT_TRUE(have) << "no control_msgs/PidState on /pid_state/state within " << kWait << " s";
  EXPECT_DOUBLE_EQ(0.5, got.error);
  EXPECT_DOUBLE_EQ(1.0, got.p_term);
  EXPECT_DOUBLE_EQ(1.0, got.output);
  EXPECT_DOUBLE_EQ(0.1, got.timestep.toSec());
}

TEST(PidRos, DynamicReconfigureStartsFromTheGainsAndSetsThem) {
  Pid pid;
  ASSERT_TRUE(pid.init(ros::NodeHandle("pid_dyn")));
  // the server wrote the Pid's bounds back as its parameters
  double i_clamp_max = 0;
  ASSERT_TRUE(ros::param::get("/pid_dyn/i_clamp_max", i_clamp_max));
  EXPECT_DOUBLE_EQ(3.0, i_clamp_max);
  ASSERT_TRUE(ros::service::waitForService("/pid_dyn/set_parameters", ros::Duration(kWait)))
      << "no /pid_dyn/set_parameters within " << kWait << " s";
  dynamic_reconfigure::Reconfigure srv;
  dynamic_reconfigure::DoubleParameter p;
  p.name = "p";
  p.value = 7.0;
  srv.request.config.doubles.push_back(p);
  ASSERT_TRUE(ros::service::call("/pid_dyn/set_parameters", srv));
  // p from the call, the rest as they were
  EXPECT_EQ((std::vector<double>{7.0, 0.5, 0.0, 3.0, -3.0}), gains(pid));
}

TEST(PidRos, InitXmlReadsTheAttributes) {
  TiXmlElement e("pid");
  e.SetAttribute("p", "2");
  e.SetAttribute("iClamp", "-3");
  e.SetAttribute("antiwindup", "1");
  Pid pid;
  ASSERT_TRUE(pid.initXml(&e));
  // i and d absent: 0
  EXPECT_EQ((std::vector<double>{2.0, 0.0, 0.0, 3.0, -3.0}), gains(pid));
  EXPECT_TRUE(pid.getGains().antiwindup_);
}

TEST(PidRos, GainsSetterSetsEveryAddedPidAndTheParameters) {
  Pid a, b;
  control_toolbox::PidGainsSetter setter;
  setter.add(&a).add(&b);
  setter.advertise("setter");
  ASSERT_TRUE(ros::service::waitForService("/setter/set_gains", ros::Duration(kWait)))
      << "no /setter/set_gains within " << kWait << " s";
  control_toolbox::SetPidGains srv;
  srv.request.p = 4.0;
  srv.request.i = 1.0;
  srv.request.i_clamp = 2.0;
  srv.request.antiwindup = true;
  ASSERT_TRUE(ros::service::call("/setter/set_gains", srv));
  for (Pid* pid : {&a, &b}) {
    EXPECT_EQ((std::vector<double>{4.0, 1.0, 0.0, 2.0, -2.0}), gains(*pid));
    EXPECT_TRUE(pid->getGains().antiwindup_);
  }
  double p = 0;
  ASSERT_TRUE(ros::param::get("/setter/p", p));
  EXPECT_DOUBLE_EQ(4.0, p);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_pid_ros");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
