// <gazebo> values in attribute form (<mu1 value="0.5"/>) as well as text form, as sdformat's URDF reader takes
// them (GetKeyValueAsString: the `value` attribute first, else the text). One test per key the core reads.
#include <gtest/gtest.h>

#include "car_sim/model.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

RobotModel with_block(const std::string& block, const LoadOptions& o = LoadOptions()) {
  return load_urdf_string(
      "<robot name='r'>\n<link name='base'><inertial><mass value='1'/>"
      "<inertia ixx='0.01' ixy='0' ixz='0' iyy='0.01' iyz='0' izz='0.01'/></inertial>"
      "<collision><geometry><box size='1 1 1'/></geometry></collision></link>\n"
      "<gazebo reference='base'>\n" + block + "\n</gazebo></robot>",
      "values.urdf", o);
}

const GazeboLinkExt& ext(const RobotModel& m) { return m.links[0].gazebo; }

}  // namespace

TEST(GazeboValues, Mu1AttributeAndText) {
  EXPECT_EQ(ext(with_block("<mu1 value='0.5'/>")).mu1, std::optional<double>(0.5));
  EXPECT_EQ(ext(with_block("<mu1>0.5</mu1>")).mu1, std::optional<double>(0.5));
}

TEST(GazeboValues, Mu2Attribute) { EXPECT_EQ(ext(with_block("<mu2 value='0.25'/>")).mu2, std::optional<double>(0.25)); }

TEST(GazeboValues, KpAttribute) { EXPECT_EQ(ext(with_block("<kp value='1e7'/>")).kp, std::optional<double>(1e7)); }

TEST(GazeboValues, KdAttribute) { EXPECT_EQ(ext(with_block("<kd value='100'/>")).kd, std::optional<double>(100.0)); }

TEST(GazeboValues, LaserRetroAttribute) {
  EXPECT_EQ(ext(with_block("<laserRetro value='200'/>")).laser_retro, std::optional<double>(200.0));
}

TEST(GazeboValues, SelfCollideAttributeTakesYes) {
  // sdformat's booleans: true/yes/1
  EXPECT_EQ(ext(with_block("<selfCollide value='yes'/>")).self_collide, std::optional<bool>(true));
  EXPECT_EQ(ext(with_block("<selfCollide value='false'/>")).self_collide, std::optional<bool>(false));
}

TEST(GazeboValues, MaterialAttribute) {
  EXPECT_EQ(ext(with_block("<material value='Gazebo/Orange'/>")).material, "Gazebo/Orange");
}

TEST(GazeboValues, AttributeWinsOverText) {
  // GetKeyValueAsString looks at the attribute first
  EXPECT_EQ(ext(with_block("<mu1 value='0.3'>0.9</mu1>")).mu1, std::optional<double>(0.3));
}

TEST(GazeboValues, MaxVelAttribute) {
  const RobotModel m = with_block("<maxVel value='0.01'/>");
  ASSERT_TRUE(ext(m).max_vel.has_value());
  EXPECT_DOUBLE_EQ(*ext(m).max_vel, 0.01);
}

TEST(GazeboValues, OtherKeysKeepTheAttributeValue) {
  // a key car does not model is kept as written (the model check lists it)
  const RobotModel m = with_block("<provideFeedback value='true'/>");
  const std::string* v = find_param(ext(m).other, "provideFeedback");
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(*v, "true");
}

TEST(GazeboValues, BadAttributeValueNamesFileLineAndElement) {
  try {
    with_block("<kp value='stiff'/>");
    FAIL() << "no error";
  } catch (const LoadError& e) {
    // line 4: the <kp> line (the document's lines: <robot>, <link>, <gazebo>, <kp>)
    EXPECT_EQ(std::string(e.what()), "values.urdf:4: gazebo[base]/kp: 'stiff' is not a number");
  }
}
