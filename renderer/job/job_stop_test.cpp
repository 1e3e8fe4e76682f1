#include "job/job_stop.h"

#include <gtest/gtest.h>

#include <thread>

namespace kiln {
namespace {

// A limit shorter than a thread takes to start is already raised when the constructor returns,
// so a job that finishes in microseconds cannot slip past it on a busy machine.
TEST(job_stop, a_limit_shorter_than_a_thread_start_is_raised_before_any_work) {
  for (int i = 0; i < 200; ++i) {
    const job_stop stop(nullptr, 1e-6);
    ASSERT_TRUE(stop.flag()->load()) << "run " << i;
    EXPECT_TRUE(stop.timed_out());
  }
}

TEST(job_stop, a_long_limit_leaves_the_flag_down_and_an_outer_flag_raises_it) {
  std::atomic<bool> outer{false};
  const job_stop stop(&outer, 60.0);
  EXPECT_FALSE(stop.flag()->load());
  outer = true;
  for (int i = 0; i < 500 && !stop.flag()->load(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_TRUE(stop.flag()->load());
  EXPECT_FALSE(stop.timed_out());
}

TEST(job_stop, without_a_limit_the_outer_flag_is_the_flag) {
  std::atomic<bool> outer{false};
  const job_stop stop(&outer, 0.0);
  EXPECT_EQ(stop.flag(), &outer);
}

}  // namespace
}  // namespace kiln
