#include "mesh/outer_loop.h"

#include <algorithm>

namespace skinslide {

Index outer_loop(const std::vector<double>& lengths, const std::vector<Index>& starts) {
  const double longest = *std::max_element(lengths.begin(), lengths.end());
  Index best = -1;
  for (Index i = 0; i < static_cast<Index>(lengths.size()); ++i) {
    if (lengths[i] < longest * (1 - kTieRelative)) continue;
    if (best < 0 || starts[i] < starts[best]) best = i;
  }
  return best;
}

double loop_length(const Positions3& p) {
  double l = 0;
  for (size_t k = 0; k < p.size(); ++k) l += (p[(k + 1) % p.size()] - p[k]).norm();
  return l;
}

}  // namespace skinslide
