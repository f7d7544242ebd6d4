// ScopedEnv (test_util.hpp), which every test that sets a search path relies on to leave the environment as it
// found it for the tests after it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "test_util.hpp"

namespace {
std::string value_of(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "<unset>";
}
}  // namespace

TEST(ScopedEnv, PutsBackAVariableThatWasSet) {
  setenv("CAR_TEST_SCOPED_ENV", "before", 1);
  {
    ScopedEnv env{{"CAR_TEST_SCOPED_ENV", "during"}};
    EXPECT_EQ(value_of("CAR_TEST_SCOPED_ENV"), "during");
    env.set("CAR_TEST_SCOPED_ENV", "again");
    EXPECT_EQ(value_of("CAR_TEST_SCOPED_ENV"), "again");
  }
  EXPECT_EQ(value_of("CAR_TEST_SCOPED_ENV"), "before");
  unsetenv("CAR_TEST_SCOPED_ENV");
}

TEST(ScopedEnv, UnsetsAVariableThatWasNotSet) {
  unsetenv("CAR_TEST_SCOPED_ENV");
  {
    ScopedEnv env{{"CAR_TEST_SCOPED_ENV", "during"}};
    EXPECT_EQ(value_of("CAR_TEST_SCOPED_ENV"), "during");
  }
  EXPECT_EQ(value_of("CAR_TEST_SCOPED_ENV"), "<unset>");
}
