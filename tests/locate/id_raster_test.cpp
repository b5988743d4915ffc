#include "locate/id_raster.h"

#include <gtest/gtest.h>

namespace skinslide {

TEST(IdRaster, TwoTrianglesSplitTheSquareAlongTheDiagonal) {
  const Positions2 net{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const IdImage img = id_raster(net, {{0, 1, 2}, {0, 2, 3}}, 8);
  ASSERT_EQ(img.size, 8);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      // Centres on the diagonal (i == j) are in both: the lower index wins.
      const std::uint32_t expected = i >= j ? 1 : 2;
      EXPECT_EQ(img.at(i, j), expected) << i << "," << j;
    }
}

TEST(IdRaster, EmptyWhereNoTriangleAndIndependentOfOrientation) {
  const Positions2 net{{0, 0}, {0.5, 0}, {0, 0.5}};
  const IdImage a = id_raster(net, {{0, 1, 2}}, 4);
  const IdImage b = id_raster(net, {{0, 2, 1}}, 4);
  EXPECT_EQ(a.ids, b.ids);
  EXPECT_EQ(a.at(0, 0), 1u);
  EXPECT_EQ(a.at(3, 3), 0u);
  EXPECT_EQ(a.at(2, 0), 0u);  // centre (0.625, 0.125) is outside
}

TEST(IdRaster, OverlapsGoToTheLowestIndexWhateverTheOrder) {
  const Positions2 net{{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  const IdImage img = id_raster(net, {{1, 3, 2}, {0, 1, 2}, {0, 1, 3}}, 16);
  // (0.9, 0.3) lies in triangles 0 (1,3,2) and 2 (0,1,3): 0 wins.
  EXPECT_EQ(img.at(14, 4), 1u);
  // (0.2, 0.1) lies only in triangle 1 and triangle 2: 1 wins.
  EXPECT_EQ(img.at(3, 1), 2u);
}

TEST(IdRaster, DegenerateTrianglesCoverNothing) {
  const Positions2 net{{0, 0}, {1, 1}, {0.5, 0.5}};
  const IdImage img = id_raster(net, {{0, 1, 2}}, 8);
  for (auto id : img.ids) EXPECT_EQ(id, 0u);
}

}  // namespace skinslide
