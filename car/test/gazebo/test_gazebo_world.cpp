// Users' own Gazebo plug-ins at the world level (docs/PLUGINS.md, docs/COMPAT-plugins.md "World and system
// plug-ins"): world plug-ins from a world's <plugin>s and system plug-ins, written against car's Gazebo 11 headers in
// the style of Gazebo's tutorials (test/gazebo/plugins/world_*.cc, system_args.cc), built as .so files by the test
// build and found on GAZEBO_PLUGIN_PATH; the World API they use (pause, reset, model insertion) and Gazebo's
// messages. dt = 0.001 s.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <thread>
#include <utility>

#include "car_sim/shared_plugin.hpp"
#include "car_sim/world.hpp"
#include "test_util.hpp"

using namespace car_sim;

namespace {

const std::string kDir = CAR_GAZEBO_TEST_PLUGINS;
const std::string kModels = std::string(CAR_SOURCE_DIR) + "/test/data/factory_models";

// The search paths set to the test plug-ins' folder and the factory's models alone for one test, put back after.
class WorldPlugins : public ::testing::Test {
 protected:
  ScopedEnv env_{{"GAZEBO_PLUGIN_PATH", kDir}, {"CMAKE_PREFIX_PATH", "/nowhere/a"}, {"LD_LIBRARY_PATH", "/nowhere/b"},
                 {"GAZEBO_MODEL_PATH", kModels}};
  void SetUp() override { world_log(); }
  // The world_events plug-in's log (test/gazebo/plugins/world_events.cc), read from the loaded library and cleared.
  static std::string world_log() {
    void* h = dlopen((kDir + "/libworld_events.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
    if (!h) return "<not loaded>";
    auto log = reinterpret_cast<const char* (*)()>(dlsym(h, "car_test_world_log"));
    auto clear = reinterpret_cast<void (*)()>(dlsym(h, "car_test_world_clear"));
    std::string s = log();
    clear();
    dlclose(h);
    return s;
  }
  // The time_reset plug-in's log and its count of calls off the loading thread (test/gazebo/plugins/time_reset.cc),
  // read from the loaded library and cleared.
  static std::pair<std::string, int> time_reset_log() {
    void* h = dlopen((kDir + "/libtime_reset.so").c_str(), RTLD_LAZY | RTLD_NOLOAD);
    if (!h) return {"<not loaded>", -1};
    auto log = reinterpret_cast<const char* (*)()>(dlsym(h, "car_test_time_reset_log"));
    auto elsewhere = reinterpret_cast<int (*)()>(dlsym(h, "car_test_time_reset_elsewhere"));
    auto clear = reinterpret_cast<void (*)()>(dlsym(h, "car_test_time_reset_clear"));
    std::pair<std::string, int> out{log(), elsewhere()};
    clear();
    dlclose(h);
    return out;
  }
};

// How many times a log has `what` ("timereset@0 reset@0" has one "timereset").
int count(const std::string& log, const std::string& what) {
  int n = 0;
  for (size_t at = log.find(what); at != std::string::npos; at = log.find(what, at + 1)) ++n;
  return n;
}

// A world "lab" without gravity, a ground plane and the given <plugin>s (and models) in <world>.
std::unique_ptr<World> lab(const std::string& inside) {
  return std::make_unique<World>(load_world_string(R"(<?xml version="1.0"?>
<sdf version="1.6"><world name="lab"><gravity>0 0 0</gravity>
  <model name="ground"><static>true</static><link name="l">
    <collision name="c"><geometry><plane><normal>0 0 1</normal><size>20 20</size></plane></geometry></collision>
  </link></model>
  )" + inside + R"(
</world></sdf>)"));
}

std::vector<std::string> messages(const World& w, const std::string& code) {
  std::vector<std::string> out;
  for (const auto& d : w.world_diagnostics())
    if (d.code == code) out.push_back(d.message);
  return out;
}

Eigen::Vector3d at(const World& w, const std::string& model) {
  return w.link_pose(model, "link").translation();
}

}  // namespace

// Gazebo's hello_world tutorial as a world plug-in: "Hello World!" once, when the world loads; not again as it runs.
TEST_F(WorldPlugins, HelloWorldPrintsOnceWhenTheWorldLoads) {
  testing::internal::CaptureStdout();
  auto w = lab(R"(<plugin name="hello" filename="libworld_hello.so"/>)");
  w->step(10);
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "Hello World!\n");
  EXPECT_TRUE(w->world_diagnostics().empty());
}

// Gazebo's parameters tutorial: the <plugin> element as written, repeated elements in their order, each value a
// string. Printed depth first, two spaces a level from <plugin> (level 0): param_list and inner hold elements, no
// text, so they have no value and print nothing; the params at levels 2 and 3.
TEST_F(WorldPlugins, ParametersSeeTheirElementsAsWritten) {
  testing::internal::CaptureStdout();
  auto w = lab(R"(<plugin name="p" filename="libworld_parameters.so">
    <param_list><param>value1</param><inner><param>v_1_1</param></inner><inner><param>v_1_2</param></inner></param_list>
    <param_list><param>value2</param></param_list>
  </plugin>)");
  EXPECT_EQ(testing::internal::GetCapturedStdout(),
            "    param=value1\n"
            "      param=v_1_1\n"
            "      param=v_1_2\n"
            "    param=value2\n");
}

// The factory tutorial: three models, one by each door, none before the first step ends (Gazebo inserts them as it
// processes its messages after a step). Where, by hand (link frames, world):
//   box: model://box's own pose (0, 0, 0.5), the link at the model frame -> (0, 0, 0.5);
//   unique_sphere: its <pose> (1, 0, 0), the link 0.5 m up in it -> (1, 0, 0.5);
//   cylinder: the message's pose (1, -2, 0) replaces the file's (0, 0, 3), the link 0.5 m up -> (1, -2, 0.5).
TEST_F(WorldPlugins, FactoryInsertsThreeModelsAtTheEndOfTheFirstStep) {
  auto w = lab(R"(<plugin name="factory" filename="libworld_factory.so"/>)");
  EXPECT_TRUE(w->world_diagnostics().empty());
  EXPECT_EQ(w->robot_count(), 0u);
  w->step(1);
  EXPECT_EQ(w->robot_names(), (std::vector<std::string>{"box", "unique_sphere", "cylinder"}));
  EXPECT_TRUE(at(*w, "box").isApprox(Eigen::Vector3d(0, 0, 0.5), 1e-12)) << at(*w, "box").transpose();
  EXPECT_TRUE(at(*w, "unique_sphere").isApprox(Eigen::Vector3d(1, 0, 0.5), 1e-12)) << at(*w, "unique_sphere").transpose();
  EXPECT_TRUE(at(*w, "cylinder").isApprox(Eigen::Vector3d(1, -2, 0.5), 1e-12)) << at(*w, "cylinder").transpose();
  w->step(10);
  EXPECT_EQ(w->robot_count(), 3u);
}

// Two factories: the second one's names are taken, so its models become NAME_0 (Gazebo's UniqueModelName).
TEST_F(WorldPlugins, ANameTakenGetsTheFirstFreeSuffix) {
  auto w = lab(R"(<plugin name="f1" filename="libworld_factory.so"/><plugin name="f2" filename="libworld_factory.so"/>)");
  w->step(1);
  EXPECT_EQ(w->robot_names(), (std::vector<std::string>{"box", "unique_sphere", "cylinder", "box_0", "unique_sphere_0",
                                                         "cylinder_0"}));
}

// A paused world's models come in at run_deferred, which a paused pacer calls (Gazebo processes its messages while
// paused too).
TEST_F(WorldPlugins, InsertionWhilePausedComesWithRunDeferred) {
  auto w = lab(R"(<plugin name="factory" filename="libworld_factory.so"/>)");
  w->set_paused(true);
  w->run_deferred();
  EXPECT_EQ(w->robot_count(), 3u);
  EXPECT_EQ(w->tick(), 0u);
}

// Load, then Init, with the world's name and pause flag; the pause event on each change of the flag only.
TEST_F(WorldPlugins, PauseEventsComeOnEachChangeOfTheFlag) {
  auto w = lab(R"(<plugin name="ev" filename="libworld_events.so"/>)");
  EXPECT_EQ(world_log(), "load lab running@0 init@0");
  w->set_paused(true);
  w->set_paused(true);
  w->set_paused(false);
  EXPECT_EQ(world_log(), "pause@0 unpause@0");
}

// World::SetPaused in WorldUpdateBegin sets car's flag (what /gazebo/pause_physics sets), with the event at the
// step's sim time (0.001 s).
TEST_F(WorldPlugins, SetPausedInAPluginPausesTheWorld) {
  auto w = lab(R"(<plugin name="ev" filename="libworld_events.so"><action>pause</action></plugin>)");
  world_log();
  w->step(1);
  EXPECT_TRUE(w->paused());
  EXPECT_EQ(world_log(), "pause@0.001");
}

// World::Reset inside WorldUpdateBegin: done at the end of that step (tick 1 -> 0), pausing for it as Gazebo's
// World::Reset does, the world plug-in's Reset at time 0; two more steps give tick 2.
TEST_F(WorldPlugins, ResetInAnUpdateComesAtTheEndOfTheStep) {
  auto w = lab(R"(<plugin name="ev" filename="libworld_events.so"><action>reset</action></plugin>)");
  world_log();
  w->step(3);
  EXPECT_EQ(w->tick(), 2u);
  EXPECT_FALSE(w->paused());
  EXPECT_EQ(world_log(), "pause@0.001 reset@0 unpause@0");
}

// reset_simulation resets the world's plug-ins (Gazebo's World::Reset); reset_world does not (gazebo_ros resets the
// models only).
TEST_F(WorldPlugins, ResetSimulationResetsTheWorldPluginsResetWorldDoesNot) {
  auto w = lab(R"(<plugin name="ev" filename="libworld_events.so"/>)");
  world_log();
  w->step(5);
  w->reset_poses();
  EXPECT_EQ(world_log(), "");
  w->reset();
  EXPECT_EQ(world_log(), "pause@0.005 reset@0 unpause@0");
}

// event::Events::timeReset is raised by Gazebo 11's World::ResetTime only (gazebo/physics/World.cc): World::ResetTime
// raises it (1), reset_world (gazebo_ros: ResetEntities(Base::MODEL)) does not touch time (0), reset_simulation
// (gazebo_ros: World::Reset, which calls ResetTime) raises it once (1): 2 in all. The plug-in calls ResetTime in
// its first WorldUpdateBegin, done at the end of that step.
TEST_F(WorldPlugins, TimeResetComesForResetTimeAndResetSimulationNotResetWorld) {
  auto w = lab(R"(<plugin name="tr" filename="libtime_reset.so"><action>resettime</action></plugin>)");
  time_reset_log();
  w->step(3);
  EXPECT_EQ(w->tick(), 2u);
  EXPECT_EQ(count(time_reset_log().first, "timereset"), 1);
  w->reset_poses();
  EXPECT_EQ(count(time_reset_log().first, "timereset"), 0);
  w->reset();
  EXPECT_EQ(count(time_reset_log().first, "timereset"), 1);
}

// World::Reset: ResetTime (time 0, then timeReset) before ResetEntities and the plug-ins' Reset: the callback reads
// SimTime 0 and comes before the plug-in's Reset.
TEST_F(WorldPlugins, TimeResetComesAtTimeZeroBeforeThePluginsReset) {
  auto w = lab(R"(<plugin name="tr" filename="libtime_reset.so"/>)");
  time_reset_log();
  w->step(5);
  w->reset();
  EXPECT_EQ(time_reset_log().first, "timereset@0 reset@0");
}

// The callback runs on the thread that resets (Gazebo: the caller of World::Reset, gazebo_ros's service thread for
// reset_simulation): a reset from another thread than the loading one is counted there, one from the loading
// thread is not.
TEST_F(WorldPlugins, TimeResetRunsOnTheThreadThatResets) {
  auto w = lab(R"(<plugin name="tr" filename="libtime_reset.so"/>)");
  time_reset_log();
  std::thread other([&] { w->reset(); });
  other.join();
  EXPECT_EQ(time_reset_log(), (std::pair<std::string, int>{"timereset@0 reset@0", 1}));
  w->reset();
  EXPECT_EQ(time_reset_log(), (std::pair<std::string, int>{"timereset@0 reset@0", 0}));
}

// The stop event once, when the world goes, before the plug-in is deleted.
TEST_F(WorldPlugins, StopComesOnceBeforeThePluginGoes) {
  auto w = lab(R"(<plugin name="ev" filename="libworld_events.so"/>)");
  w->step(2);
  world_log();
  w->stop();
  w.reset();
  EXPECT_EQ(world_log(), "stop@0.002 unload@0.002");
}

// A model plug-in in <world>: Gazebo's wrong-type message, with what it is and what the place takes; the world goes on.
TEST_F(WorldPlugins, AModelPluginInTheWorldIsTheWrongType) {
  auto w = lab(R"(<plugin name="push" filename="libmodel_push.so"/>)");
  EXPECT_EQ(messages(*w, "plugin-not-loaded"),
            std::vector<std::string>{
                "plug-in 'push' of world 'lab' failed to load: World[lab] is attempting to load a plugin, but detected "
                "an incorrect plugin type. Plugin filename[libmodel_push.so] name[push]: it is a model plug-in "
                "(GZ_REGISTER_MODEL_PLUGIN); a <plugin> in <world> takes a world plug-in (GZ_REGISTER_WORLD_PLUGIN); "
                "world 'lab' goes on without it"});
  w->step(1);
  EXPECT_EQ(w->tick(), 1u);
}

// A world plug-in in a model: the same message from the model's side; the model stays.
TEST_F(WorldPlugins, AWorldPluginInAModelIsTheWrongType) {
  auto w = lab(R"(<model name="crate"><pose>0 0 2 0 0 0</pose><link name="link">
    <inertial><mass>1</mass></inertial>
    <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision></link>
    <plugin name="hello" filename="libworld_hello.so"/></model>)");
  std::vector<std::string> got;
  for (const auto& d : w->robot("crate").config.diagnostics)
    if (d.code == "plugin-not-loaded") got.push_back(d.message);
  EXPECT_EQ(got, std::vector<std::string>{
                     "plug-in 'hello' of model 'crate' failed to load: Model[crate] is attempting to load a plugin, but "
                     "detected an incorrect plugin type. Plugin filename[libworld_hello.so] name[hello]: it is a world "
                     "plug-in (GZ_REGISTER_WORLD_PLUGIN); a model's <plugin> takes a model plug-in "
                     "(GZ_REGISTER_MODEL_PLUGIN); the model goes on without it"});
}

// A world plug-in whose file is nowhere: Gazebo's "Failed to load plugin", the folders searched, and the line.
TEST_F(WorldPlugins, AMissingFileIsAWarningWithThePathsSearched) {
  auto w = lab(R"(<plugin name="gone" filename="libnot_there.so"/>)");
  EXPECT_EQ(messages(*w, "plugin-unknown"),
            std::vector<std::string>{"Failed to load plugin libnot_there.so: no such file in GAZEBO_PLUGIN_PATH, the "
                                     "ROS library folders or LD_LIBRARY_PATH (searched: " +
                                     kDir + ":/nowhere/a/lib:/nowhere/b); world 'lab' goes on without it"});
  EXPECT_EQ(w->world_diagnostics().at(0).line, 6);
}

// An exception out of a world plug-in's Load (here car's transport refusing a topic it does not offer) names the
// plug-in and the world; the world goes on.
TEST_F(WorldPlugins, AnExceptionInLoadNamesPluginAndWorld) {
  auto w = lab(R"(<plugin name="ev" filename="libworld_events.so"><action>topic</action></plugin>)");
  EXPECT_EQ(messages(*w, "plugin-not-loaded"),
            std::vector<std::string>{
                "plug-in 'ev' of world 'lab' failed to load: Load threw: "
                "transport::Node::Advertise<msgs::Factory>(\"~/world_control\"): car's transport offers only ~/factory "
                "(/gazebo/lab/factory), the world's model factory; world 'lab' goes on without it"});
  w->step(1);
}

// gazebo_ros's api plug-in named in a world: car's node is it, nothing loads (an info line says so).
TEST_F(WorldPlugins, GazeboRosOwnPluginInAWorldLoadsNothing) {
  auto w = lab(R"(<plugin name="ros" filename="libgazebo_ros_api_plugin.so"/>)");
  ASSERT_EQ(w->world_diagnostics().size(), 1u);
  EXPECT_EQ(w->world_diagnostics()[0].severity, Severity::Info);
  EXPECT_EQ(w->world_diagnostics()[0].message,
            "libgazebo_ros_api_plugin.so is gazebo_ros's own, which car's node is: nothing to load");
}

// gzserver -s: Load(argc, argv) with the server's command line, then Init.
TEST_F(WorldPlugins, ASystemPluginGetsTheCommandLineThenInit) {
  auto w = lab("");
  testing::internal::CaptureStdout();
  const auto found = w->load_system_plugin("libsystem_args.so", {"gzserver", "-s", "libsystem_args.so"});
  EXPECT_EQ(testing::internal::GetCapturedStdout(),
            "system plug-in: 3 args: gzserver -s libsystem_args.so\nsystem plug-in: init\n");
  EXPECT_TRUE(found.empty());
}

// A world plug-in given as -s: the wrong type, in Gazebo's words for the server ("System").
TEST_F(WorldPlugins, AWorldPluginGivenAsASystemPluginIsTheWrongType) {
  auto w = lab("");
  const auto found = w->load_system_plugin("libworld_hello.so", {"gzserver"});
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].message,
            "plug-in 'libworld_hello.so' of the server failed to load: System is attempting to load a plugin, but "
            "detected an incorrect plugin type. Plugin filename[libworld_hello.so] name[libworld_hello.so]: it is a "
            "world plug-in (GZ_REGISTER_WORLD_PLUGIN); gzserver's -s takes a system plug-in "
            "(GZ_REGISTER_SYSTEM_PLUGIN); the server goes on without it");
}
