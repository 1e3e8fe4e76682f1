#include "core/format_number.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace kiln {
namespace {

TEST(format_number, drops_trailing_zeros_and_keeps_the_sign) {
  EXPECT_EQ(format_number(-0.5), "-0.5");
  EXPECT_EQ(format_number(3.0), "3");
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(0.0), "0");
}

TEST(format_number, rounds_to_six_significant_digits) {
  EXPECT_EQ(format_number(3.14159265), "3.14159");
  EXPECT_EQ(format_number(1234567.0), "1.23457e+06");
  EXPECT_EQ(format_number(1e30), "1e+30");
  EXPECT_EQ(format_number(1.5e-7), "1.5e-07");
}

TEST(format_number, names_non_finite_values) {
  EXPECT_EQ(format_number(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(format_number(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_number(-std::numeric_limits<double>::infinity()), "-inf");
}

}  // namespace
}  // namespace kiln
