#include "core/number_format.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace skinslide {
namespace {

TEST(NumberFormat, DoublesComeOutShortestAndReadBackExactly) {
  EXPECT_EQ(format_double(0.1), "0.1");
  EXPECT_EQ(format_double(1e-5), "1e-05");
  EXPECT_EQ(format_double(-3.0), "-3");
  EXPECT_EQ(format_double(0.1 + 0.2), "0.30000000000000004");
  // The longest texts a double has still fit the in-place buffer.
  for (double x : {-2.2250738585072014e-308, 5e-324, -1.7976931348623157e308,
                   -0.00012345678901234567, std::nextafter(1.0, 2.0)}) {
    const DoubleText t = double_text(x);
    ASSERT_LE(t.size, sizeof t.chars);
    EXPECT_EQ(std::string(t.view()), format_double(x));
    EXPECT_EQ(parse_double(t.view()), x);
  }
  EXPECT_EQ(format_double(-2.2250738585072014e-308), "-2.2250738585072014e-308");
}

TEST(NumberFormat, CountsTakeTheSingularForOneOnly) {
  EXPECT_EQ(counted(1, "patch", "patches"), "1 patch");
  EXPECT_EQ(counted(0, "patch", "patches"), "0 patches");
  EXPECT_EQ(counted(2, "frame", "frames"), "2 frames");
}

TEST(NumberFormat, ParsingTakesWholeNumbersOnly) {
  EXPECT_EQ(parse_double("+1.5"), 1.5);
  EXPECT_EQ(parse_double("-2.5e3"), -2500.0);
  EXPECT_FALSE(parse_double("1x"));
  EXPECT_FALSE(parse_double(""));
  EXPECT_FALSE(parse_double("+"));
  EXPECT_TRUE(std::isnan(*parse_double("nan")));
  // Beyond a double's range: an infinity (overflow), or a zero (underflow) with its sign.
  EXPECT_EQ(parse_double("1e999"), std::numeric_limits<double>::infinity());
  EXPECT_EQ(parse_double("-123.4e307"), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(parse_double("1e-400"), 0.0);
  EXPECT_EQ(parse_double("0.000001e-320"), 0.0);
  EXPECT_TRUE(std::signbit(*parse_double("-1e-400")));
  EXPECT_EQ(parse_double("1e-310"), 1e-310);  // subnormal: read as is
  EXPECT_EQ(parse_double("1e-99999999999999999999"), 0.0);
  EXPECT_EQ(parse_double("1e+99999999999999999999"), std::numeric_limits<double>::infinity());
  EXPECT_FALSE(parse_double("1e-400x"));
  EXPECT_EQ(parse_integer("+42"), 42);
  EXPECT_EQ(parse_integer("-7"), -7);
  EXPECT_FALSE(parse_integer("4.0"));
  EXPECT_FALSE(parse_integer("99999999999999999999"));  // beyond long long
}

}  // namespace
}  // namespace skinslide
