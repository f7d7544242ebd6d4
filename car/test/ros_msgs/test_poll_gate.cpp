// The publishing thread's gate on roscpp's publish queues (src/ros/poll_gate.hpp), with the test as roscpp's poll
// thread: connected to roscpp's PollManager, whose thread is never started here, so rounds come only from on_round().
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "poll_gate.hpp"

namespace {

TEST(PollGate, BeyondItsBoundThePublisherWaitsForThePollThreadsNextRound) {
  car_ros::PollGate gate(100);
  gate.connect();
  // 60 bytes handed over: within the bound of 100
  gate.published(60);
  std::atomic<bool> done{false};
  // 60 more: 120 > 100, so it waits for a round
  std::thread publisher([&] {
    gate.published(60);
    done = true;
  });
  // a publisher that did not wait would be done by now, on any machine that ran it at all
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(done) << "the publisher went on before the poll thread's round";
  gate.on_round();
  publisher.join();
  EXPECT_TRUE(done);
  EXPECT_EQ(gate.rounds(), 1u);
}

TEST(PollGate, ARoundEmptiesTheCountOfWhatWasHandedOver) {
  car_ros::PollGate gate(100);
  gate.connect();
  gate.published(40);
  gate.published(50);
  EXPECT_EQ(gate.handed(), 90u);
  gate.on_round();
  EXPECT_EQ(gate.handed(), 0u);
  gate.published(30);
  EXPECT_EQ(gate.handed(), 30u);
}

TEST(PollGate, APollThreadThatNeverComesRoundHoldsThePublisherOnlyForItsBound) {
  // roscpp shut down: no round will come; published() returns after its 1 s bound instead of hanging the node
  car_ros::PollGate gate(100);
  gate.connect();
  gate.published(500);
  EXPECT_EQ(gate.rounds(), 0u);
}

}  // namespace
