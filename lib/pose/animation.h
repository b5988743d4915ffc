// Animation sampling: a channel's value at a time, the nodes' local transforms at a time, and the
// times at which a clip is sampled. glTF 2.0 section 3.11 and Appendix C (interpolation).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "pose/rig.h"

namespace skinslide {

/// Value of `sampler` at time `t` (seconds), `sampler.width` components. Before the first key
/// the first value holds, after the last the last. STEP holds key k on [t_k, t_k+1); LINEAR
/// interpolates linearly, or by slerp along the shorter arc when `is_rotation`; CUBICSPLINE is
/// the cubic Hermite spline of Appendix C, with tangents scaled by the key interval. Rotations
/// come back normalised.
/// \pre sampler.times is non-empty and strictly increasing; values sized as documented in rig.h.
Eigen::VectorXd sample(const AnimationSampler& sampler, double t, bool is_rotation);

/// Spherical linear interpolation from `a` to `b` (unit quaternions), along the shorter arc.
Quat slerp(const Quat& a, const Quat& b, double s);

/// Local transform of every node at time `t` of `animation`: the rest transforms, with each
/// translation/rotation/scale channel's path replaced by its sampled value. `animation` null =
/// the rest pose.
std::vector<NodeTransform> animated_transforms(const Rig& rig, const Animation* animation,
                                               double t);

/// Morph weights (#targets) at time `t` of `animation`: rig.weights, replaced as a whole by the
/// clip's weights channel when it has one (glTF 2.0 section 3.11: the sampler's output holds one
/// value per target per key, interpolated like any vector). `animation` null = rig.weights.
std::vector<double> animated_weights(const Rig& rig, const Animation* animation, double t);

/// Times start, start + 1/fps, ... up to `end` (a time within 1e-9 s of `end` counts as `end`).
/// \pre fps > 0
std::vector<double> fps_times(const Animation& animation, double fps);

/// Every key time of every channel of the clip, ascending, each once.
std::vector<double> keyframe_times(const Animation& animation);

}  // namespace skinslide
