// skinslide.write_cache / read_cache: PC2 and MDD point caches on numpy arrays, through the
// command line's own reader and writer (io/point_cache.h; every byte in lib/io/README.md): the
// Blender add-on bakes its slide to a PC2 with them, bit for bit the cache the command writes.

#include "cache_module.h"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "core/error.h"
#include "io/point_cache.h"

namespace py = pybind11;

namespace skinslide {
namespace {

using SampleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

[[noreturn]] void usage(const std::string& what) { throw Error(ErrorKind::Usage, what); }

// The header write_cache is asked for, checked as the reader checks a file's (a header the
// reader would refuse is a usage error here, with the reader's message).
CacheHeader requested_header(const std::string& path, py::ssize_t samples, py::ssize_t points,
                             double start_frame, double sample_rate,
                             const std::optional<std::vector<double>>& times) {
  const std::optional<CacheFormat> format = cache_format(path);
  if (!format) usage(path + ": a point cache's name ends in .pc2 or .mdd");
  if (samples < 1 || points < 1 || samples > INT32_MAX || points > INT32_MAX)
    usage("samples must be an array of shape (samples, points, 3), at least one of each");
  CacheHeader h;
  h.format = *format;
  h.samples = static_cast<std::int32_t>(samples);
  h.points = static_cast<std::int32_t>(points);
  h.start_frame = static_cast<float>(start_frame);
  h.sample_rate = static_cast<float>(sample_rate);
  if (h.format == CacheFormat::Mdd) {
    if (!times || static_cast<py::ssize_t>(times->size()) != samples)
      usage(path + ": an MDD cache needs times, one a sample (seconds)");
    for (const double t : *times) h.times.push_back(static_cast<float>(t));
  } else if (times) {
    usage(path + ": times are MDD's; a PC2 has start_frame and sample_rate");
  }
  try {
    parse_cache_header(path, h.format, encode_header(h), cache_bytes(h));
  } catch (const Error& e) {
    usage(e.what());
  }
  return h;
}

void write_cache(const std::string& path, const py::handle& object, double start_frame,
                 double sample_rate, const std::optional<std::vector<double>>& times) {
  const SampleArray a = SampleArray::ensure(object);
  if (!a || a.ndim() != 3 || a.shape(2) != 3)
    usage("samples must be an array of shape (samples, points, 3)");
  const CacheHeader h =
      requested_header(path, a.shape(0), a.shape(1), start_frame, sample_rate, times);
  const double* data = a.data();
  py::gil_scoped_release released;
  CacheWriter writer(path, h);
  const std::size_t floats = 3 * static_cast<std::size_t>(h.points);
  CacheSample xyz(floats);
  for (std::size_t k = 0; k < static_cast<std::size_t>(h.samples); ++k) {
    // Each coordinate rounded to float32 once, as the command writes a slid cache.
    for (std::size_t i = 0; i < floats; ++i) xyz[i] = static_cast<float>(data[k * floats + i]);
    writer.write_sample(k, xyz);
  }
  writer.commit();
}

py::tuple read_cache(const std::string& path) {
  const CacheReader reader(path);
  const CacheHeader& h = reader.header();
  py::array_t<float> samples(
      {static_cast<py::ssize_t>(h.samples), static_cast<py::ssize_t>(h.points), py::ssize_t{3}});
  float* out = samples.mutable_data();
  {
    py::gil_scoped_release released;
    for (std::size_t k = 0; k < static_cast<std::size_t>(h.samples); ++k) {
      const CacheSample xyz = reader.sample(k);
      out = std::copy(xyz.begin(), xyz.end(), out);
    }
  }
  py::dict header;
  header["format"] = to_string(h.format);
  header["points"] = h.points;
  header["samples"] = h.samples;
  std::vector<long long> frames;
  for (std::size_t k = 0; k < static_cast<std::size_t>(h.samples); ++k)
    frames.push_back(sample_frame(h, k));
  header["frames"] = frames;
  if (h.format == CacheFormat::Pc2) {
    header["start_frame"] = h.start_frame;
    header["sample_rate"] = h.sample_rate;
  } else {
    header["times"] = h.times;
  }
  return py::make_tuple(samples, header);
}

}  // namespace

void add_cache_functions(py::module_& m) {
  m.def("write_cache", &write_cache, py::arg("path"), py::arg("samples"), py::kw_only(),
        py::arg("start_frame") = 0.0, py::arg("sample_rate") = 1.0, py::arg("times") = py::none(),
        "Writes a point cache, the format from the name (.pc2, .mdd): samples (samples, points, "
        "3), each coordinate rounded to float32 once. PC2: sample k is frame start_frame + k x "
        "sample_rate; MDD: times, one a sample in seconds. Written atomically (a temporary "
        "renamed into place), as the command writes its caches.");
  m.def("read_cache", &read_cache, py::arg("path"),
        "Reads a PC2 or MDD point cache: (samples (samples, points, 3) float32, header), the "
        "header a dict: format, points, samples, frames (each sample's frame number), and "
        "start_frame, sample_rate (PC2) or times (MDD). The command line's reader and checks.");
}

}  // namespace skinslide
