// Numbers typed by a person or read from a file (swa/app/number.h): the whole text or nothing.

#include <limits>

#include <gtest/gtest.h>

#include "swa/app/number.h"

namespace swa::app {
namespace {

TEST(Number, IntegerIsTheWholeTextInDecimalWithinBounds) {
  // GIVEN texts that are, and are not, integers in [0, 255]
  EXPECT_EQ(parseInteger("0", 0, 255), 0);
  EXPECT_EQ(parseInteger("255", 0, 255), 255);
  EXPECT_EQ(parseInteger("010", 0, 255), 10);  // decimal, never octal
  EXPECT_EQ(parseInteger("-3", -5, 5), -3);
  // THEN anything else is refused, not half-read
  for (const char* bad : {"", " 1", "1 ", "1x", "0x1", "1.0", "256", "-1", "99999999999999999999"}) {
    EXPECT_FALSE(parseInteger(bad, 0, 255).has_value()) << "'" << bad << "'";
  }
}

TEST(Number, RealIsTheWholeTextFiniteWithinBounds) {
  EXPECT_DOUBLE_EQ(*parseReal("0.5", 0, 1), 0.5);
  EXPECT_DOUBLE_EQ(*parseReal("1e-3", 0, 1), 0.001);
  EXPECT_DOUBLE_EQ(*parseReal("-0", 0, 1), 0.0);
  for (const char* bad : {"", " 1", "1 ", "1s", "nan", "inf", "-inf", "1.5", "-0.1", "1e999"}) {
    EXPECT_FALSE(parseReal(bad, 0, 1).has_value()) << "'" << bad << "'";
  }
  EXPECT_FALSE(parseReal("1e308", 0, std::numeric_limits<double>::max() / 10).has_value());
}

TEST(Number, FormattedAsAPersonWritesIt) {
  EXPECT_EQ(formatNumber(0), "0");
  EXPECT_EQ(formatNumber(2), "2");
  EXPECT_EQ(formatNumber(0.05), "0.05");
  EXPECT_EQ(formatNumber(1e-3), "0.001");
  EXPECT_EQ(formatNumber(1e6), "1000000");
  EXPECT_EQ(formatNumber(-2.5), "-2.5");
}

}  // namespace
}  // namespace swa::app
