// world_tool check's reading of a world (car_sim::check_world_file; docs/COMPAT-validation.md "world_tool check"):
// one rule a test, each with its exact finding. Fixtures: test/data/worlds/bad/.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "car_sim/description.hpp"
#include "test_util.hpp"
#include "validate.hpp"

using namespace car_sim;

namespace {

WorldCheck check_bad(const std::string& name) { return check_world_file(data_path("worlds/bad/" + name)); }

// The one finding a fixture gives; fails naming them all when there is not exactly one.
Diagnostic only_finding(const WorldCheck& c) {
  std::string all;
  for (const auto& f : c.findings) all += f.code + " " + f.element + ": " + f.message + "\n";
  EXPECT_EQ(c.findings.size(), 1u) << all;
  return c.findings.empty() ? Diagnostic{} : c.findings.front();
}

}  // namespace

TEST(WorldCheck, APoseOfFiveNumbersAndAWordIsAnError) {
  // <pose>1 2 three 0 0 0</pose>: 'three' is no decimal, so the text is not 6 numbers
  const WorldCheck c = check_bad("bad_pose.world");
  const Diagnostic f = only_finding(c);
  EXPECT_EQ(f.severity, Severity::Error);
  EXPECT_EQ(f.code, "pose-malformed");
  EXPECT_EQ(f.element, "world[bad]/model[post]/pose");
  EXPECT_EQ(f.message, "pose '1 2 three 0 0 0' is not 6 numbers (x y z roll pitch yaw)");
  EXPECT_EQ(c.world, nullptr);  // an error comes before the load
}

TEST(WorldCheck, APoseWithANonFiniteNumberIsAnError) {
  const Diagnostic f = only_finding(check_bad("pose_nan.world"));
  EXPECT_EQ(f.code, "pose-malformed");
  EXPECT_EQ(f.element, "world[bad]/model[post]/pose");
  EXPECT_EQ(f.message, "pose 'nan 0 0.5 0 0 0' has a non-finite value");
}

TEST(WorldCheck, AHexadecimalIsNoDecimalInAPose) {
  // strtod reads 0x10 as 16; Python's float(), the tool's reader before, refuses it: six tokens, five numbers
  EXPECT_EQ(detail::pose_problem("0x10 0 0 0 0 0", nullptr), "pose '0x10 0 0 0 0 0' is not 6 numbers (x y z roll pitch yaw)");
}

TEST(WorldCheck, ABlankPoseIsTheIdentityAndNoFinding) {
  std::vector<double> v = {1.0};
  EXPECT_EQ(detail::pose_problem("  \n ", &v), "");
  EXPECT_TRUE(v.empty());
}

TEST(WorldCheck, AnIncludesPoseIsHeldToTheSameRuleByTheFlattener) {
  // <include><pose>0 0 zero 0 0 0</pose>: the flattener refuses it with the check's words
  const Diagnostic f = only_finding(check_bad("include_bad_pose.world"));
  EXPECT_EQ(f.code, "world-unreadable");
  EXPECT_EQ(f.element, "world[bad]/include[0]/pose");
  EXPECT_EQ(f.message, "pose '0 0 zero 0 0 0' is not 6 numbers (x y z roll pitch yaw)");
}

TEST(WorldCheck, AGeometryWithNoShapeIsAnError) {
  const Diagnostic f = only_finding(check_bad("empty_geometry.world"));
  EXPECT_EQ(f.severity, Severity::Error);
  EXPECT_EQ(f.code, "geometry-empty");
  EXPECT_EQ(f.element, "world[bad]/model[ghost]/link[l]/collision[c]/geometry");
  EXPECT_EQ(f.message, "<geometry> holds no shape");
}

TEST(WorldCheck, AGeometrySdfDoesNotKnowIsAnError) {
  const Diagnostic f = only_finding(check_bad("unknown_geometry.world"));
  EXPECT_EQ(f.severity, Severity::Error);
  EXPECT_EQ(f.code, "geometry-unknown");
  EXPECT_EQ(f.element, "world[bad]/model[blob]/link[l]/collision[c]/geometry/torus");
  // the list of sdformat 12's sdf/1.9/geometry.sdf, sorted
  EXPECT_EQ(f.message,
            "unknown geometry <torus> (SDF knows box, capsule, cylinder, ellipsoid, empty, heightmap, image, mesh, "
            "plane, polyline, sphere)");
}

TEST(WorldCheck, AMeshWithoutUriIsAnError) {
  const Diagnostic f = only_finding(check_bad("mesh_no_uri.world"));
  EXPECT_EQ(f.severity, Severity::Error);
  EXPECT_EQ(f.code, "uri-missing");
  EXPECT_EQ(f.element, "world[bad]/model[statue]/link[l]/visual[v]/geometry/mesh");
  EXPECT_EQ(f.message, "<mesh> has no <uri>");
}

TEST(WorldCheck, AShapeCarDoesNotSimulateIsAWarningAndTheWorldLoads) {
  const WorldCheck c = check_bad("unsimulated_geometry.world");
  ASSERT_FALSE(c.findings.empty());
  const Diagnostic& f = c.findings.front();  // the check's own, before the loader's
  EXPECT_EQ(f.severity, Severity::Warning);
  EXPECT_EQ(f.code, "geometry-unsimulated");
  EXPECT_EQ(f.element, "world[bad]/model[pill]/link[l]/collision[c]/geometry/capsule");
  EXPECT_EQ(f.message, "<capsule> is not simulated by car; ignored");
  ASSERT_NE(c.world, nullptr);
  EXPECT_EQ(c.world->models.size(), 1u);
}

TEST(WorldCheck, PluginStateAndGuiBlocksAreNotLookedInto) {
  // the rules alone (the loader has its own say on these poses)
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse("<world name='w'><gui><camera name='c'><pose>gui</pose></camera></gui>"
                      "<plugin name='p' filename='libx.so'><pose>plugin</pose></plugin>"
                      "<state world_name='w'><model name='m'><pose>state</pose></model></state></world>"),
            tinyxml2::XML_SUCCESS);
  for (const auto& f : detail::check_world_xml(doc.RootElement()))
    ADD_FAILURE() << f.code << " " << f.element << ": " << f.message;
}

TEST(WorldCheck, AFileThatCannotBeFlattenedIsUnreadable) {
  const Diagnostic f = only_finding(check_world_file("/nonexistent/no.world"));
  EXPECT_EQ(f.severity, Severity::Error);
  EXPECT_EQ(f.code, "world-unreadable");
  EXPECT_EQ(f.element, "");
  EXPECT_EQ(f.message, "no such file");
}

TEST(WorldCheck, TheLoadersRefusalIsAWorldLoadError) {
  // a dynamic link of mass 0: the check's rules pass, the loader refuses (sdf_world.cpp convert)
  const WorldCheck c = check_bad("massless.world");
  const Diagnostic f = only_finding(c);
  EXPECT_EQ(f.code, "world-load");
  EXPECT_EQ(f.element, "");
  EXPECT_EQ(f.message, "model[crate]/link[body]/inertial: a dynamic link needs a mass > 0");
  EXPECT_EQ(c.world, nullptr);
}

TEST(WorldCheck, AnIncludeThatResolvesNowhereIsAWarningAndTheRestLoads) {
  ScopedEnv env{{"GAZEBO_MODEL_PATH", "/nonexistent/models"}};
  const WorldCheck c = check_bad("missing_model.world");
  const Diagnostic f = only_finding(c);
  EXPECT_EQ(f.severity, Severity::Warning);
  EXPECT_EQ(f.code, "include-missing");
  EXPECT_EQ(f.element, "world[bad]/include[0]/uri");
  EXPECT_EQ(f.message.rfind("cannot find 'model://no_such_model' (model path: /nonexistent/models:", 0), 0u) << f.message;
  ASSERT_NE(c.world, nullptr);
  EXPECT_TRUE(c.world->models.empty());
}

TEST(WorldCheck, AnIso88591WorldIsLoadedWithItsNamesInUtf8) {
  // 'm\xe9' in ISO-8859-1 is the byte 0xE9; in UTF-8 it is 0xC3 0xA9
  const std::string path = (std::filesystem::temp_directory_path() / "car_check_latin1.world").string();
  std::ofstream(path) << "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n<sdf version=\"1.6\"><world name=\"w\">"
                         "<model name=\"m\xe9\"><static>true</static><link name=\"l\"/></model></world></sdf>\n";
  const WorldCheck c = check_world_file(path);
  std::filesystem::remove(path);
  ASSERT_NE(c.world, nullptr);
  ASSERT_EQ(c.world->models.size(), 1u);
  EXPECT_EQ(c.world->models[0].name, "m\xc3\xa9");
}

TEST(WorldCheck, AWorldThatIsNotUtf8AndSaysNothingElseIsUnreadable) {
  // the byte 0xE9 alone, with no encoding declared: not UTF-8 (a lead byte 0b1110xxxx needs two more 0b10xxxxxx)
  const std::string path = (std::filesystem::temp_directory_path() / "car_check_not_utf8.world").string();
  std::ofstream(path) << "<sdf version=\"1.6\"><world name=\"w\"><model name=\"m\xe9\"><static>true</static>"
                         "<link name=\"l\"/></model></world></sdf>\n";
  const WorldCheck c = check_world_file(path);
  std::filesystem::remove(path);
  const Diagnostic f = only_finding(c);
  EXPECT_EQ(f.code, "world-unreadable");
  EXPECT_EQ(f.message,
            "not UTF-8 text (byte 0xe9; car reads worlds in UTF-8, and in ISO-8859-1 where their declaration says so)");
  EXPECT_EQ(c.world, nullptr);
}
