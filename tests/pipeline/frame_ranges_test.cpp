#include "pipeline/frame_ranges.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace skinslide {
namespace {

std::vector<long long> frames_in(const std::string& spec, long long lo, long long hi) {
  const std::vector<FrameRange> r = parse_frame_ranges(spec);
  std::vector<long long> out;
  for (long long f = lo; f <= hi; ++f)
    if (in_frame_ranges(r, f)) out.push_back(f);
  return out;
}

std::string usage_error(const std::string& spec) {
  try {
    parse_frame_ranges(spec);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    return e.what();
  }
  return "";
}

TEST(FrameRanges, SelectsRangesStepsAndLists) {
  EXPECT_EQ(frames_in("3-6", 0, 20), (std::vector<long long>{3, 4, 5, 6}));
  EXPECT_EQ(frames_in("1-20:5", 0, 30), (std::vector<long long>{1, 6, 11, 16}));
  EXPECT_EQ(frames_in("1-20x5", 0, 30), (std::vector<long long>{1, 6, 11, 16}));
  EXPECT_EQ(frames_in("3,7,12-14", 0, 30), (std::vector<long long>{3, 7, 12, 13, 14}));
  EXPECT_EQ(frames_in(" 4 , 2 ", 0, 10), (std::vector<long long>{2, 4}));
  EXPECT_EQ(frames_in("0", 0, 3), (std::vector<long long>{0}));
  // A chunk running past the last frame selects the frames there are.
  EXPECT_EQ(frames_in("9-20", 1, 10), (std::vector<long long>{9, 10}));
}

TEST(FrameRanges, RejectsMalformedSpecsNamingTheTerm) {
  EXPECT_EQ(
      usage_error("5-3"),
      "--frames: '5-3' runs backwards; expected frame numbers like 1-100, 1-100:5 or 3,7,12-20");
  EXPECT_NE(usage_error("").find("'' is empty"), std::string::npos);
  EXPECT_NE(usage_error("1,,3").find("'' is empty"), std::string::npos);
  EXPECT_NE(usage_error("1-10:0").find("step below 1"), std::string::npos);
  EXPECT_NE(usage_error("1-10:").find("no step"), std::string::npos);
  EXPECT_NE(usage_error("5:2").find("step but no range"), std::string::npos);
  EXPECT_NE(usage_error("a-b").find("'a-b' is not a frame number"), std::string::npos);
  EXPECT_NE(usage_error("-3").find("not a frame number"), std::string::npos);
  EXPECT_NE(usage_error("1-99999999999999999999").find("not a frame number"), std::string::npos);
}

TEST(FrameRanges, FrameNumberIsTheLastDigitRunBeforeTheExtension) {
  EXPECT_EQ(frame_number("shot/arm.0042.obj"), 42);
  EXPECT_EQ(frame_number("f7.obj"), 7);
  EXPECT_EQ(frame_number("take2/walk_v3.0100.glb"), 100);
  EXPECT_EQ(frame_number("out/RiggedSimple.0003.glb"), 3);
  EXPECT_EQ(frame_number("walk_v3.obj"), 3);
  EXPECT_EQ(frame_number("2/bind.obj"), std::nullopt);
  EXPECT_EQ(frame_number("99999999999999999999.obj"), std::nullopt);
}

TEST(FrameRanges, FrameSequenceIsTheFileNameWithItsFrameNumberAsAHash) {
  EXPECT_EQ(frame_sequence("frames/arm.0001.obj"), "arm.#.obj");
  EXPECT_EQ(frame_sequence("other/arm.0002.obj"), frame_sequence("frames/arm.0001.obj"));
  EXPECT_EQ(frame_sequence("take2/walk_v3.0100.glb"), "walk_v3.#.glb");
  EXPECT_EQ(frame_sequence("f7_final.obj"), "f#_final.obj");
  EXPECT_NE(frame_sequence("arm.0001.glb"), frame_sequence("arm.0002.obj"));
  EXPECT_EQ(frame_sequence("data/elbow/bind.obj"), std::nullopt);
}

}  // namespace
}  // namespace skinslide
