// An option's one declaration (core/option.h) read the ways its clients read it: its figure, its
// range check, its words, on a toy options struct.
#include "core/option.h"

#include <cmath>

#include <gtest/gtest.h>

namespace skinslide {
namespace {

enum class Shape { Round, Square };

struct ToyOptions {
  int count = 3;
  double share = 0.25;
  Shape shape = Shape::Square;
};

constexpr Words<Shape, 3> kShapes{
    "shape", {{{"round", Shape::Round}, {"square", Shape::Square}, {"box", Shape::Square}}}};

OptionTable<ToyOptions> toy_table() {
  using O = ToyOptions;
  return {{"count", "How many", NumberOption<O, int>{&O::count, 1, 10}},
          {"share-of-it", "How much", NumberOption<O, double>{&O::share, 0.0, 0.5}},
          {"shape", "Which", word_option(&O::shape, kShapes)}};
}

TEST(Option, FiguresAreTheMembersUnderTheirApiNamesInTableOrder) {
  const Figures f = option_figures(toy_table(), ToyOptions{});
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0].key, "count");
  EXPECT_EQ(std::get<long long>(f[0].value), 3);
  EXPECT_EQ(f[1].key, "share_of_it");
  EXPECT_EQ(std::get<double>(f[1].value), 0.25);
  EXPECT_EQ(f[2].key, "shape");
  EXPECT_EQ(std::get<std::string>(f[2].value), "square") << "a value's first word";
}

TEST(Option, RangesAreInclusiveAndRefuseNaN) {
  ToyOptions o;
  o.count = 10;
  o.share = 0.0;
  EXPECT_NO_THROW(check_ranges(toy_table(), o));
  o.count = 11;
  try {
    check_ranges(toy_table(), o);
    FAIL() << "11 is past 10";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_STREQ(e.what(), "count = 11 is outside [1, 10]");
  }
  o.count = 1;
  o.share = std::nan("");
  EXPECT_THROW(check_ranges(toy_table(), o), Error);
}

TEST(Option, AWordSetsItsValueAndAnUnknownWordNamesEveryWord) {
  const OptionTable<ToyOptions> table = toy_table();
  const auto& shape = std::get<WordOption<ToyOptions>>(table[2].value);
  EXPECT_EQ(shape.words, (std::vector<std::string>{"round", "square", "box"}));
  ToyOptions o;
  shape.set(o, "round");
  EXPECT_EQ(o.shape, Shape::Round);
  shape.set(o, "box");
  EXPECT_EQ(o.shape, Shape::Square);
  EXPECT_EQ(shape.get(o), "square") << "another spelling reads back as the value's name";
  try {
    shape.set(o, "oval");
    FAIL() << "not a word of the option";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_STREQ(e.what(), "unknown shape 'oval' (round, square, box)");
  }
}

}  // namespace
}  // namespace skinslide
