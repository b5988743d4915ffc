// Reads an EXR back with OpenEXR itself, for the tests of what skinslide writes.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>

namespace skinslide::test {

/// An EXR's channels and attributes as read. Planes are stored as the file stores them:
/// row 0 = the top of the image.
struct ExrContents {
  int width = 0;
  int height = 0;
  Imf::Compression compression = Imf::NO_COMPRESSION;
  std::map<std::string, Imf::PixelType> types;
  std::map<std::string, std::vector<std::uint32_t>> uints;
  std::map<std::string, std::vector<float>> floats;
  std::map<std::string, std::string> strings;
  std::map<std::string, int> ints;

  /// Sample at (i, j) with j counted from the BOTTOM (v = 0), as skinslide's images are.
  std::uint32_t uint_at(const std::string& c, int i, int j) const {
    return uints.at(c)[size_t(height - 1 - j) * width + i];
  }
  float float_at(const std::string& c, int i, int j) const {
    return floats.at(c)[size_t(height - 1 - j) * width + i];
  }
};

inline ExrContents read_exr(const std::string& path) {
  Imf::InputFile file(path.c_str());
  const Imf::Header& h = file.header();
  ExrContents out;
  const Imath::Box2i dw = h.dataWindow();
  out.width = dw.max.x - dw.min.x + 1;
  out.height = dw.max.y - dw.min.y + 1;
  out.compression = h.compression();
  const size_t n = size_t(out.width) * out.height;
  Imf::FrameBuffer fb;
  for (auto it = h.channels().begin(); it != h.channels().end(); ++it) {
    const std::string name = it.name();
    out.types[name] = it.channel().type;
    if (it.channel().type == Imf::UINT) {
      auto& v = out.uints[name];
      v.resize(n);
      fb.insert(name, Imf::Slice(Imf::UINT, reinterpret_cast<char*>(v.data()), 4, 4 * out.width));
    } else if (it.channel().type == Imf::FLOAT) {
      auto& v = out.floats[name];
      v.resize(n);
      fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(v.data()), 4, 4 * out.width));
    }
  }
  file.setFrameBuffer(fb);
  file.readPixels(dw.min.y, dw.max.y);
  for (auto it = h.begin(); it != h.end(); ++it) {
    if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
      out.strings[it.name()] = s->value();
    if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&it.attribute()))
      out.ints[it.name()] = i->value();
  }
  return out;
}

}  // namespace skinslide::test
