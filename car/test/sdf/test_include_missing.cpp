// An <include> that resolves nowhere: sdformat (9, Gazebo 11's, as 12) reports it and goes on, and Gazebo 11 loads
// the rest; car leaves it out with a warning "include-missing" (docs/COMPAT-validation.md).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "car_sim/description.hpp"
#include "car_sim/sdf_model.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

const std::string kCrate =
    "<model name='crate'><pose>0 0 0.5 0 0 0</pose><link name='body'><inertial><mass>1</mass><inertia><ixx>0.1</ixx>"
    "<iyy>0.1</iyy><izz>0.1</izz></inertia></inertial><collision name='c'><geometry><box><size>1 1 1</size></box>"
    "</geometry></collision></link></model>";

const Diagnostic* include_warning(const std::vector<Diagnostic>& ds) {
  for (const auto& d : ds)
    if (d.code == "include-missing") return &d;
  return nullptr;
}

// GAZEBO_MODEL_PATH set to one folder that holds nothing, for the messages' model path
struct EmptyModelPath {
  ScopedEnv env{{"GAZEBO_MODEL_PATH", "/nonexistent/models"}};
};

std::string write_temp(const std::string& name, const std::string& text) {
  const std::filesystem::path p = std::filesystem::temp_directory_path() / name;
  std::ofstream(p) << text;
  return p.string();
}

}  // namespace

TEST(IncludeMissing, AWorldLoadsWithoutItAndWarns) {
  EmptyModelPath path;
  const WorldDescription d = load_world_string(
      "<sdf version='1.6'><world name='w'>" + kCrate + "<include><uri>model://nope</uri></include></world></sdf>",
      "w.world");
  ASSERT_EQ(d.models.size(), 1u);
  EXPECT_EQ(d.models[0].name, "crate");
  const Diagnostic* w = include_warning(d.diagnostics);
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->severity, Severity::Warning);
  EXPECT_EQ(w->message.rfind("Unable to find uri[model://nope] (model path: /nonexistent/models:", 0), 0u)
      << w->message;
  EXPECT_NE(w->message.find("): left out, as Gazebo 11 leaves it out"), std::string::npos) << w->message;
}

TEST(IncludeMissing, AnIncludeWithoutUriIsLeftOutAndWarns) {
  const WorldDescription d =
      load_world_string("<sdf version='1.6'><world name='w'>" + kCrate + "<include></include></world></sdf>", "w.world");
  ASSERT_EQ(d.models.size(), 1u);
  const Diagnostic* w = include_warning(d.diagnostics);
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->message.rfind("<include> element missing 'uri' attribute", 0), 0u) << w->message;
}

TEST(IncludeMissing, AnSdfRobotLoadsWithoutItAndWarns) {
  EmptyModelPath path;
  const SdfRobot r = load_sdf_model_string(
      "<sdf version='1.6'><model name='bot'><link name='base'><inertial><mass>1</mass><inertia><ixx>0.1</ixx>"
      "<iyy>0.1</iyy><izz>0.1</izz></inertia></inertial></link><include><uri>model://nope</uri></include></model>"
      "</sdf>",
      "bot.sdf");
  ASSERT_EQ(r.model.links.size(), 1u);
  ASSERT_NE(include_warning(r.model.diagnostics), nullptr);
}

TEST(IncludeMissing, ADatabaseSpawnOfAMissingModelNamesThePathsSearched) {
  // spawn_model -database: the world holds only the include, so nothing is left to spawn: an error saying why
  EmptyModelPath path;
  try {
    load_sdf_model_string(
        "<sdf version='1.4'><world name='default'><include><uri>model://no_such_bot</uri></include></world></sdf>",
        "-database");
    FAIL() << "spawned nothing without an error";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("Unable to find uri[model://no_such_bot] (model path: /nonexistent/models:"),
              std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("; the world holds no model to spawn"), std::string::npos) << e.what();
  }
}

TEST(IncludeMissing, TheFlattenerLeavesItOutWhenAskedForWarnings) {
  EmptyModelPath path;
  const std::string file = write_temp("missing_include.world",
      "<sdf version='1.6'><world name='w'>" + kCrate + "<include><uri>model://nope</uri></include></world></sdf>");
  std::vector<Diagnostic> warnings;
  const std::string flat = flatten_world_file(file, &warnings);
  EXPECT_EQ(flat.find("include"), std::string::npos) << flat;
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0].element, "world[w]/include[1]/uri");
  // without a list for warnings it stays an error (world_tool flatten's strict mode)
  EXPECT_THROW(flatten_world_file(file), LoadError);
}
