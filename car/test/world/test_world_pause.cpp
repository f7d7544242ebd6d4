// World's calls for Gazebo's world-level plug-ins (docs/PLUGINS.md, docs/COMPAT-plugins.md "World and system
// plug-ins"): the pause flag and its hooks, the stop hooks, work deferred to the end of a step, and the world's own
// <plugin>s read from the SDF. dt = 0.001 s.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "car_sim/world.hpp"

using namespace car_sim;

// A pause hook runs on each change of the flag only, with the new value (Gazebo's World::SetPaused returns early
// when nothing changes); the flag does not stop step(), which is the pacer's to honour.
TEST(WorldPause, HooksRunOnEachChangeOnly) {
  World w(empty_world());
  std::vector<bool> seen;
  w.add_pause_hook([&](bool p) { seen.push_back(p); });
  EXPECT_FALSE(w.paused());
  w.set_paused(false);
  w.set_paused(true);
  w.set_paused(true);
  EXPECT_TRUE(w.paused());
  w.step(2);
  EXPECT_EQ(w.tick(), 2u);
  w.set_paused(false);
  EXPECT_EQ(seen, (std::vector<bool>{true, false}));
}

// reset_simulation pauses for the reset and puts the flag back, as Gazebo's World::Reset: a running world's hooks
// see true then false; a paused one's see nothing.
TEST(WorldPause, ResetPausesForItsWork) {
  World w(empty_world());
  std::vector<bool> seen;
  w.add_pause_hook([&](bool p) { seen.push_back(p); });
  w.reset();
  EXPECT_EQ(seen, (std::vector<bool>{true, false}));
  seen.clear();
  w.set_paused(true);
  w.reset();
  EXPECT_EQ(seen, (std::vector<bool>{true}));
}

// A removed hook is not called again.
TEST(WorldPause, ARemovedHookIsNotCalled) {
  World w(empty_world());
  int calls = 0;
  const uint64_t id = w.add_pause_hook([&](bool) { ++calls; });
  w.remove_step_hook(id);
  w.set_paused(true);
  EXPECT_EQ(calls, 0);
}

// The stop hooks run once: at the first stop(), not at a second one nor in the destructor after it.
TEST(WorldStop, HooksRunOnce) {
  int calls = 0;
  {
    World w(empty_world());
    w.add_stop_hook([&] { ++calls; });
    w.stop();
    w.stop();
  }
  EXPECT_EQ(calls, 1);
  {
    World w(empty_world());
    w.add_stop_hook([&] { ++calls; });
  }
  EXPECT_EQ(calls, 2);
}

// Deferred work runs at the end of the next step (after its tick is counted: it sees tick 1), in the order given;
// work deferred by deferred work waits for the step after.
TEST(WorldDeferred, RunsAtTheEndOfTheNextStep) {
  World w(empty_world());
  std::vector<std::string> log;
  w.defer([&] { log.push_back("a@" + std::to_string(w.tick())); });
  w.defer([&] {
    log.push_back("b@" + std::to_string(w.tick()));
    w.defer([&] { log.push_back("c@" + std::to_string(w.tick())); });
  });
  EXPECT_TRUE(log.empty());
  w.step(1);
  EXPECT_EQ(log, (std::vector<std::string>{"a@1", "b@1"}));
  w.step(1);
  EXPECT_EQ(log, (std::vector<std::string>{"a@1", "b@1", "c@2"}));
}

// run_deferred runs it now, without a step (what a paused pacer calls).
TEST(WorldDeferred, RunDeferredRunsItNow) {
  World w(empty_world());
  int calls = 0;
  w.defer([&] { ++calls; });
  w.run_deferred();
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(w.tick(), 0u);
  w.step(1);
  EXPECT_EQ(calls, 1);
}

// The <plugin>s directly in <world>: name, file, elements as written (flattened a/b), the line; a model's are not
// among them.
TEST(WorldDescriptionPlugins, ReadsTheWorldsOwnPlugins) {
  const WorldDescription d = load_world_string(R"(<?xml version="1.0"?>
<sdf version="1.6"><world name="lab">
  <plugin name="a" filename="liba.so"><velocity>2.5</velocity><pid><p>3</p></pid></plugin>
  <model name="m"><static>true</static><link name="l"/><plugin name="inner" filename="libm.so"/></model>
  <plugin name="b" filename="libb.so"/>
</world></sdf>)");
  ASSERT_EQ(d.plugins.size(), 2u);
  EXPECT_EQ(d.plugins[0].name, "a");
  EXPECT_EQ(d.plugins[0].filename, "liba.so");
  EXPECT_EQ(d.plugins[0].params,
            (ParamList{{"velocity", "2.5"}, {"pid/p", "3"}}));
  EXPECT_EQ(d.plugins[0].line, 3);
  EXPECT_EQ(d.plugins[1].name, "b");
  EXPECT_EQ(d.plugins[1].line, 5);
}

// A world plug-in whose file is nowhere leaves the world as it is, with the warning.
TEST(WorldDescriptionPlugins, AMissingWorldPluginIsAWarningAndTheWorldRuns) {
  World w(load_world_string(R"(<?xml version="1.0"?>
<sdf version="1.6"><world name="lab"><plugin name="gone" filename="/nowhere/libgone.so"/></world></sdf>)"));
  ASSERT_EQ(w.world_diagnostics().size(), 1u);
  EXPECT_EQ(w.world_diagnostics()[0].code, "plugin-unknown");
  EXPECT_EQ(w.world_diagnostics()[0].element, "world/plugin[gone]");
  w.step(1);
  EXPECT_EQ(w.tick(), 1u);
}
