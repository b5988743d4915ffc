#include "pose/animation.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace skinslide {

Quat slerp(const Quat& a, const Quat& b, double s) {
  // glTF 2.0 Appendix C: flip one end to take the shorter arc; near-parallel ends fall back to a
  // normalised lerp, where sin(angle) would lose all precision.
  double d = a.coeffs().dot(b.coeffs());
  Eigen::Vector4d bb = b.coeffs();
  if (d < 0) {
    d = -d;
    bb = -bb;
  }
  Eigen::Vector4d r;
  if (d > 0.9995) {
    r = (1 - s) * a.coeffs() + s * bb;
  } else {
    const double angle = std::acos(d);
    const double sa = std::sin(angle);
    r = (std::sin((1 - s) * angle) / sa) * a.coeffs() + (std::sin(s * angle) / sa) * bb;
  }
  Quat q;
  q.coeffs() = r.normalized();
  return q;
}

Eigen::VectorXd sample(const AnimationSampler& sampler, double t, bool is_rotation) {
  const std::vector<double>& times = sampler.times;
  const int w = sampler.width;
  const std::size_t n = times.size();
  SKINSLIDE_CHECK(n > 0, "animation sampler without keys");
  const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
  SKINSLIDE_CHECK(sampler.values.size() == n * w * (cubic ? 3 : 1), "sampler values size");
  // Key k's value: for CUBICSPLINE the middle of (in-tangent, value, out-tangent).
  auto value = [&](std::size_t k) {
    return Eigen::Map<const Eigen::VectorXd>(sampler.values.data() + (cubic ? 3 * k + 1 : k) * w,
                                             w);
  };
  auto finish = [&](Eigen::VectorXd v) {
    if (is_rotation && v.norm() > 0) v.normalize();
    return v;
  };
  if (t <= times.front() || n == 1) return finish(value(0));
  if (t >= times.back()) return finish(value(n - 1));
  // k: the last key with times[k] <= t, so that t is in [t_k, t_k+1).
  const std::size_t k =
      static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  const double td = times[k + 1] - times[k];
  const double s = (t - times[k]) / td;
  switch (sampler.interpolation) {
    case Interpolation::Step:
      return finish(value(k));
    case Interpolation::Linear: {
      if (!is_rotation) return (1 - s) * value(k) + s * value(k + 1);
      Quat a, b;
      a.coeffs() = value(k);
      b.coeffs() = value(k + 1);
      return slerp(a, b, s).coeffs();
    }
    case Interpolation::CubicSpline: {
      auto out_tangent = [&](std::size_t j) {
        return Eigen::Map<const Eigen::VectorXd>(sampler.values.data() + (3 * j + 2) * w, w);
      };
      auto in_tangent = [&](std::size_t j) {
        return Eigen::Map<const Eigen::VectorXd>(sampler.values.data() + (3 * j) * w, w);
      };
      const double s2 = s * s, s3 = s2 * s;
      const Eigen::VectorXd v =
          (2 * s3 - 3 * s2 + 1) * value(k) + td * (s3 - 2 * s2 + s) * out_tangent(k) +
          (-2 * s3 + 3 * s2) * value(k + 1) + td * (s3 - s2) * in_tangent(k + 1);
      return finish(v);
    }
  }
  return finish(value(k));
}

std::vector<NodeTransform> animated_transforms(const Rig& rig, const Animation* animation,
                                               double t) {
  std::vector<NodeTransform> local(rig.nodes.size());
  for (std::size_t i = 0; i < rig.nodes.size(); ++i) local[i] = rig.nodes[i].rest;
  if (animation == nullptr) return local;
  for (const AnimationChannel& c : animation->channels) {
    if (c.path == ChannelPath::Weights) continue;
    SKINSLIDE_CHECK(c.node >= 0 && c.node < static_cast<Index>(local.size()), "channel node");
    NodeTransform& x = local[c.node];
    const bool rotation = c.path == ChannelPath::Rotation;
    const Eigen::VectorXd v = sample(c.sampler, t, rotation);
    switch (c.path) {
      case ChannelPath::Translation:
        x.translation = v.head<3>();
        break;
      case ChannelPath::Rotation:
        x.rotation.coeffs() = v.head<4>();
        break;
      case ChannelPath::Scale:
        x.scale = v.head<3>();
        break;
      case ChannelPath::Weights:
        break;
    }
  }
  return local;
}

std::vector<double> animated_weights(const Rig& rig, const Animation* animation, double t) {
  std::vector<double> w = rig.weights;
  if (animation == nullptr) return w;
  for (const AnimationChannel& c : animation->channels) {
    if (c.path != ChannelPath::Weights) continue;
    SKINSLIDE_CHECK(c.sampler.width == static_cast<int>(w.size()),
                    "weights channel width differs from the target count");
    const Eigen::VectorXd v = sample(c.sampler, t, false);
    for (std::size_t i = 0; i < w.size(); ++i) w[i] = v[static_cast<Eigen::Index>(i)];
  }
  return w;
}

std::vector<double> fps_times(const Animation& animation, double fps) {
  SKINSLIDE_CHECK(fps > 0, "fps must be positive");
  std::vector<double> times;
  // Each time from its frame number, never by accumulation, so no drift over long clips.
  for (long k = 0;; ++k) {
    const double t = animation.start + k / fps;
    if (t > animation.end + 1e-9) break;
    times.push_back(std::min(t, animation.end));
  }
  return times;
}

std::vector<double> keyframe_times(const Animation& animation) {
  std::vector<double> times;
  for (const AnimationChannel& c : animation.channels)
    times.insert(times.end(), c.sampler.times.begin(), c.sampler.times.end());
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

}  // namespace skinslide
