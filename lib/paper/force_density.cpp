#include "paper/force_density.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace skinslide {

std::vector<double> force_densities(const std::vector<double>& lengths, Density density,
                                    double q_floor) {
  std::vector<double> q(lengths.size(), 1.0);
  if (density == Density::Uniform || lengths.empty()) return q;
  const double lmax = *std::max_element(lengths.begin(), lengths.end());
  if (!(lmax > 0) || !std::isfinite(lmax))
    throw Error(ErrorKind::Input, "every bar of the patch has zero (or non-finite) length");
  if (density == Density::Paper) {
    for (size_t i = 0; i < q.size(); ++i) q[i] = std::max(1.0 - lengths[i] / lmax, q_floor);
    return q;
  }
  // Inverse: a collapsed bar would get an infinite q; clamping its length keeps the system finite.
  const double lclamp = 1e-12 * lmax;
  double lmin = lmax;
  for (double l : lengths) lmin = std::min(lmin, std::max(l, lclamp));
  for (size_t i = 0; i < q.size(); ++i)
    q[i] = std::max(lmin / std::max(lengths[i], lclamp), q_floor);
  return q;
}

}  // namespace skinslide
