#include "pose/animation.h"

#include <cmath>

#include <gtest/gtest.h>

namespace skinslide {
namespace {

AnimationSampler scalar_keys(Interpolation i) {
  // A 1-wide sampler is enough for translation-style interpolation; values by hand.
  AnimationSampler s;
  s.interpolation = i;
  s.width = 1;
  s.times = {0, 1, 2};
  s.values = {0, 10, 20};
  return s;
}

TEST(Sample, StepHoldsEachKeyUntilTheNext) {
  const AnimationSampler s = scalar_keys(Interpolation::Step);
  EXPECT_EQ(sample(s, -1, false)[0], 0);
  EXPECT_EQ(sample(s, 0.5, false)[0], 0);
  EXPECT_EQ(sample(s, 1.0, false)[0], 10);
  EXPECT_EQ(sample(s, 1.99, false)[0], 10);
  EXPECT_EQ(sample(s, 2.0, false)[0], 20);
  EXPECT_EQ(sample(s, 7, false)[0], 20);
}

TEST(Sample, LinearInterpolatesAndClampsOutsideTheKeys) {
  const AnimationSampler s = scalar_keys(Interpolation::Linear);
  EXPECT_DOUBLE_EQ(sample(s, 0.25, false)[0], 2.5);
  EXPECT_DOUBLE_EQ(sample(s, 1.5, false)[0], 15);
  EXPECT_DOUBLE_EQ(sample(s, -3, false)[0], 0);
  EXPECT_DOUBLE_EQ(sample(s, 3, false)[0], 20);
}

TEST(Sample, CubicSplineIsTheHermiteOfAppendixC) {
  // Keys at t = 0 and 2 (interval 2): (in, value, out) = (9, 1, 2) and (3, 5, 9).
  AnimationSampler s;
  s.interpolation = Interpolation::CubicSpline;
  s.width = 1;
  s.times = {0, 2};
  s.values = {9, 1, 2, 3, 5, 9};
  // t = 1, s = 0.5: (2s^3-3s^2+1) 1 + 2 (s^3-2s^2+s) 2 + (-2s^3+3s^2) 5 + 2 (s^3-s^2) 3
  //               = 0.5 + 0.5 + 2.5 - 0.75 = 2.75
  EXPECT_DOUBLE_EQ(sample(s, 1, false)[0], 2.75);
  EXPECT_DOUBLE_EQ(sample(s, 0, false)[0], 1);  // the value, not the in-tangent
  EXPECT_DOUBLE_EQ(sample(s, 2, false)[0], 5);
  // t = 0.5, s = 0.25: 0.84375 + 2*0.140625*2 + 0.15625*5 + 2*(-0.046875)*3 = 1.90625
  EXPECT_DOUBLE_EQ(sample(s, 0.5, false)[0], 1.90625);
}

Eigen::Vector4d axis_angle_z(double degrees) {
  const double h = degrees * M_PI / 360;
  return Eigen::Vector4d(0, 0, std::sin(h), std::cos(h));  // x y z w
}

TEST(Sample, LinearRotationIsSlerpAlongTheShorterArc) {
  AnimationSampler s;
  s.interpolation = Interpolation::Linear;
  s.width = 4;
  s.times = {0, 1};
  const Eigen::Vector4d a = axis_angle_z(0), b = axis_angle_z(90);
  s.values = {a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]};
  for (double t : {0.25, 0.5, 0.9}) {
    const Eigen::VectorXd q = sample(s, t, true);
    EXPECT_NEAR((q - axis_angle_z(90 * t)).norm(), 0, 1e-15) << t;
  }
  // The same end rotation written as -q: still the 90-degree path, not the 270-degree one.
  s.values = {a[0], a[1], a[2], a[3], -b[0], -b[1], -b[2], -b[3]};
  EXPECT_NEAR((sample(s, 0.5, true) - axis_angle_z(45)).norm(), 0, 1e-15);
  // Nearly equal ends (normalised lerp branch) stay unit.
  const Eigen::Vector4d c = axis_angle_z(0.01);
  s.values = {a[0], a[1], a[2], a[3], c[0], c[1], c[2], c[3]};
  EXPECT_NEAR(sample(s, 0.5, true).norm(), 1, 1e-15);
  EXPECT_NEAR((sample(s, 0.5, true) - axis_angle_z(0.005)).norm(), 0, 1e-12);
}

TEST(Sample, CubicRotationsComeBackNormalised) {
  AnimationSampler s;
  s.interpolation = Interpolation::CubicSpline;
  s.width = 4;
  s.times = {0, 1};
  const Eigen::Vector4d a = axis_angle_z(0), b = axis_angle_z(90);
  s.values.assign(24, 0.0);
  for (int c = 0; c < 4; ++c) {
    s.values[4 + c] = a[c];
    s.values[16 + c] = b[c];
  }
  const Eigen::VectorXd q = sample(s, 0.5, true);
  EXPECT_NEAR(q.norm(), 1, 1e-15);
  // Zero tangents: the Hermite midpoint is (a + b) / 2, normalised = the 45-degree rotation.
  EXPECT_NEAR((q - axis_angle_z(45)).norm(), 0, 1e-15);
}

TEST(Times, FpsCoversTheClipWithoutDriftAndKeyframesAreTheUnion) {
  Animation a;
  a.start = 0;
  a.end = 1;
  EXPECT_EQ(fps_times(a, 4), (std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
  a.end = 0.9;
  EXPECT_EQ(fps_times(a, 4), (std::vector<double>{0, 0.25, 0.5, 0.75}));
  // RiggedSimple's clip: 1/24 s to 50/24 s at 24 fps gives its 50 keys' times.
  a.start = 1.0 / 24;
  a.end = 50.0 / 24;
  const std::vector<double> t = fps_times(a, 24);
  ASSERT_EQ(t.size(), 50u);
  EXPECT_DOUBLE_EQ(t.back(), 50.0 / 24);

  Animation b;
  AnimationChannel c1, c2;
  c1.sampler.times = {0, 1, 2};
  c2.sampler.times = {0.5, 1, 3};
  b.channels = {c1, c2};
  EXPECT_EQ(keyframe_times(b), (std::vector<double>{0, 0.5, 1, 2, 3}));
}

TEST(AnimatedTransforms, ChannelsReplaceOnlyTheirPath) {
  Rig rig;
  rig.nodes.resize(2);
  rig.nodes[1].rest.translation = Vec3(1, 2, 3);
  rig.nodes[1].rest.scale = Vec3(2, 2, 2);
  Animation a;
  AnimationChannel c;
  c.node = 1;
  c.path = ChannelPath::Translation;
  c.sampler.times = {0, 1};
  c.sampler.values = {0, 0, 0, 10, 0, 0};
  a.channels = {c};
  const std::vector<NodeTransform> x = animated_transforms(rig, &a, 0.5);
  EXPECT_EQ(x[1].translation, Vec3(5, 0, 0));
  EXPECT_EQ(x[1].scale, Vec3(2, 2, 2));
  EXPECT_EQ(animated_transforms(rig, nullptr, 0.5)[1].translation, Vec3(1, 2, 3));
}

}  // namespace
}  // namespace skinslide
