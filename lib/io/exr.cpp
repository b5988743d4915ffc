#include "io/exr.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <set>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include "core/check.h"
#include "core/error.h"
#include "io/atomic_write.h"

namespace skinslide {
namespace {

// OpenEXR writes the line-offset table last and seeks back to fill it in, so the whole file is
// assembled in memory and handed to write_file_atomic() in one piece: no partial file on disk.
class StringOStream : public Imf::OStream {
 public:
  StringOStream() : Imf::OStream("<memory>") {}

  void write(const char c[], int n) override {
    const size_t end = pos_ + static_cast<size_t>(n);
    if (end > bytes_.size()) bytes_.resize(end);
    std::memcpy(bytes_.data() + pos_, c, static_cast<size_t>(n));
    pos_ = end;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = static_cast<size_t>(pos); }

  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
  size_t pos_ = 0;
};

// Rows top first, as EXR stores them.
template <class T>
std::vector<T> flipped(std::span<const T> plane, int width, int height) {
  std::vector<T> out(plane.size());
  const size_t w = static_cast<size_t>(width);
  for (int r = 0; r < height; ++r)
    std::copy_n(plane.data() + static_cast<size_t>(height - 1 - r) * w, w,
                out.data() + static_cast<size_t>(r) * w);
  return out;
}

}  // namespace

std::string exr_bytes(const ExrImage& image) {
  SKINSLIDE_CHECK(image.width >= 1 && image.height >= 1, "EXR image size");
  const size_t n = static_cast<size_t>(image.width) * image.height;
  std::set<std::string> names;
  for (const auto& c : image.uint_channels) {
    SKINSLIDE_CHECK(c.values.size() == n, "EXR channel " + c.name + " size");
    SKINSLIDE_CHECK(names.insert(c.name).second, "EXR channel " + c.name + " repeats");
  }
  for (const auto& c : image.float_channels) {
    SKINSLIDE_CHECK(c.values.size() == n, "EXR channel " + c.name + " size");
    SKINSLIDE_CHECK(names.insert(c.name).second, "EXR channel " + c.name + " repeats");
  }

  std::vector<std::vector<std::uint32_t>> uints;
  std::vector<std::vector<float>> floats;
  for (const auto& c : image.uint_channels)
    uints.push_back(flipped(c.values, image.width, image.height));
  for (const auto& c : image.float_channels)
    floats.push_back(flipped(c.values, image.width, image.height));

  try {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.lineOrder() = Imf::INCREASING_Y;
    for (const auto& [name, value] : image.string_attributes)
      header.insert(name, Imf::StringAttribute(value));
    for (const auto& [name, value] : image.int_attributes)
      header.insert(name, Imf::IntAttribute(value));

    Imf::FrameBuffer frame;
    const size_t row_u = sizeof(std::uint32_t) * image.width;
    const size_t row_f = sizeof(float) * image.width;
    for (size_t k = 0; k < uints.size(); ++k) {
      const std::string& name = image.uint_channels[k].name;
      header.channels().insert(name, Imf::Channel(Imf::UINT));
      frame.insert(name, Imf::Slice(Imf::UINT, reinterpret_cast<char*>(uints[k].data()),
                                    sizeof(std::uint32_t), row_u));
    }
    for (size_t k = 0; k < floats.size(); ++k) {
      const std::string& name = image.float_channels[k].name;
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      frame.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(floats[k].data()),
                                    sizeof(float), row_f));
    }

    StringOStream stream;
    {
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    }  // the destructor completes the file (the line-offset table)
    return stream.take();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(ErrorKind::Output, std::string("cannot encode EXR: ") + e.what());
  }
}

void write_exr(const std::string& path, const ExrImage& image) {
  std::string bytes;
  try {
    bytes = exr_bytes(image);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Output) throw;
    throw Error(ErrorKind::Output, path + ": " + e.what());
  }
  write_file_atomic(path, bytes);
}

}  // namespace skinslide
