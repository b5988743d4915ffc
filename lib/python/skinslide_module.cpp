// The Python module `skinslide` (pybind11): skinslide.h's set-up and slide on numpy arrays, the
// file readers, and skinslide::Error as Python exceptions. lib/python/README.md is its manual.
//
// Arrays: float64 positions are used in place when C-contiguous (else converted once); a slide
// writes straight into the numpy array it returns. The GIL is released while setting up and
// sliding, so a thread pool slides frames in parallel with the bits of a serial run.

#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "cache_module.h"
#include "core/version.h"
#include "core/nearest_name.h"
#include "core/option.h"
#include "io/mesh_formats.h"
#include "io/patch_file.h"
#include "io/vertex_list.h"
#include "skinslide.h"

namespace py = pybind11;
using namespace skinslide;

namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using IndexArray = py::array_t<Index, py::array::c_style | py::array::forcecast>;

// ---- Errors -----------------------------------------------------------------------------------

// skinslide.Error and one subclass per ErrorKind, each with a `kind` class attribute. Created
// once with the module and kept for the interpreter's life.
struct ErrorClasses {
  PyObject* base = nullptr;
  std::map<ErrorKind, PyObject*> by_kind;
};
ErrorClasses& error_classes() {
  static ErrorClasses classes;
  return classes;
}

void add_errors(py::module_& m) {
  ErrorClasses& c = error_classes();
  c.base = PyErr_NewExceptionWithDoc(
      "skinslide.Error",
      "A skinslide error: str(e) says what was wrong (and where); e.kind is 'usage', 'input', "
      "'output', 'numeric' or 'internal', as the command line's exit codes 2, 3, 4, 5 and 1.",
      PyExc_Exception, nullptr);
  m.add_object("Error", py::handle(c.base));
  const std::pair<ErrorKind, const char*> kinds[] = {{ErrorKind::Usage, "usage"},
                                                     {ErrorKind::Input, "input"},
                                                     {ErrorKind::Output, "output"},
                                                     {ErrorKind::Numeric, "numeric"},
                                                     {ErrorKind::Internal, "internal"}};
  for (const auto& [kind, word] : kinds) {
    std::string name = word;
    name[0] = static_cast<char>(name[0] - 'a' + 'A');
    name += "Error";
    PyObject* cls = PyErr_NewException(("skinslide." + name).c_str(), c.base, nullptr);
    py::setattr(cls, "kind", py::str(word));
    m.add_object(name.c_str(), py::handle(cls));
    c.by_kind[kind] = cls;
  }
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      PyErr_SetString(error_classes().by_kind.at(e.kind()), e.what());
    }
  });
}

[[noreturn]] void usage(const std::string& what) { throw Error(ErrorKind::Usage, what); }

// ---- Arguments --------------------------------------------------------------------------------

// A (#V, 3) float64 array.
DoubleArray points(const py::handle& object, const char* name) {
  DoubleArray a = DoubleArray::ensure(object);
  if (!a || a.ndim() != 2 || a.shape(1) != 3)
    usage(std::string(name) + " must be an array of shape (vertices, 3)");
  return a;
}

std::vector<Index> indices(const py::handle& object, const char* name) {
  IndexArray a = IndexArray::ensure(object);
  if (!a || a.ndim() != 1) usage(std::string(name) + " must be a 1-D array of integers");
  return std::vector<Index>(a.data(), a.data() + a.size());
}

// Faces: a (faces, corners) integer array; with face_sizes, the flat vertex list; else a
// sequence of polygons.
void read_faces(const py::handle& faces, const py::object& face_sizes,
                std::vector<Index>& face_vertices, std::vector<Index>& sizes) {
  if (!face_sizes.is_none()) {
    face_vertices = indices(faces, "faces (with face_sizes)");
    sizes = indices(face_sizes, "face_sizes");
    return;
  }
  if (py::isinstance<py::array>(faces) &&
      py::array(py::reinterpret_borrow<py::array>(faces)).ndim() == 2) {
    IndexArray a = IndexArray::ensure(faces);
    if (!a) usage("faces must hold integers");
    face_vertices.assign(a.data(), a.data() + a.size());
    sizes.assign(static_cast<size_t>(a.shape(0)), static_cast<Index>(a.shape(1)));
    return;
  }
  for (const py::handle polygon : faces) {
    const std::vector<Index> ids = indices(polygon, "each face");
    face_vertices.insert(face_vertices.end(), ids.begin(), ids.end());
    sizes.push_back(static_cast<Index>(ids.size()));
  }
}

// Patches: one selection (a sequence of face ids) or several (a sequence of such).
std::vector<std::vector<Index>> read_patches(const py::handle& patches) {
  const bool one = py::isinstance<py::array>(patches) || py::len(patches) == 0 ||
                   !(py::isinstance<py::sequence>(patches[py::int_(0)]) ||
                     py::isinstance<py::array>(patches[py::int_(0)]));
  if (one) return {indices(patches, "patches")};
  std::vector<std::vector<Index>> out;
  for (const py::handle p : patches) out.push_back(indices(p, "each patch"));
  return out;
}

// options[key] as a T (removed from `options`), or `value` when absent.
template <class T>
T take(py::dict& options, const char* key, T value) {
  if (!options.contains(key)) return value;
  try {
    value = options[key].cast<T>();
  } catch (const py::cast_error&) {
    usage(std::string(key) + " must be " +
          (std::is_same_v<T, std::string> ? "a string"
           : std::is_same_v<T, double>    ? "a number"
                                          : "an integer"));
  }
  PyDict_DelItemString(options.ptr(), key);
  return value;
}

// The options of `table` taken from keyword arguments into `options`: numbers as they are, words
// by their option's words (\throw Error(Usage) naming an unknown one).
template <class Options>
void take_options(py::dict& kwargs, Options& options) {
  std::vector<const Option<Options>*> given;
  for (const Option<Options>& option : option_table<Options>()) {
    const std::string key = api_name(option.name);
    if (kwargs.contains(key.c_str())) given.push_back(&option);
    std::visit(
        [&](const auto& value) {
          if constexpr (requires { value.member; })
            options.*value.member = take(kwargs, key.c_str(), options.*value.member);
          else
            value.set(options, take(kwargs, key.c_str(), value.get(options)));
        },
        option.value);
  }
  // An option that needs another's word (the elastic search's internals: solver = 'search').
  for (const Option<Options>* option : given) {
    if (!option->needs_option) continue;
    for (const Option<Options>& other : option_table<Options>())
      if (other.name == option->needs_option) {
        const std::string word = std::get<WordOption<Options>>(other.value).get(options);
        if (word != option->needs_word)
          usage(api_name(option->name) + " applies to " + api_name(other.name) + " '" +
                option->needs_word + "' only, not to " + api_name(other.name) + " '" + word + "'");
      }
  }
}

// Slider's own keyword arguments, as its py::init below declares them: with the methods' options,
// the names an unknown keyword may have meant.
const std::vector<std::string> kSliderKeywords = {
    "method", "pins", "weights", "strength", "corners", "outer_loop_vertices", "face_sizes",
    "threads"};

// "unknown option rotation_fit; the nearest option is rotation_fits": among Slider's keywords and
// every method's options.
std::string unknown_option(const std::string& name) {
  std::vector<std::string> names = kSliderKeywords;
  for_each_method([&](const std::string&, const auto& table) {
    for (const auto& option : table) names.push_back(api_name(option.name));
  });
  return "unknown option " + name + "; the nearest option is " + nearest_name(name, names);
}

// The method and its options from keyword arguments; what is left over is refused, by name.
SlideOptions slide_options(const std::string& method, py::dict options) {
  SlideOptions out = parse_method(method);
  std::visit([&](auto& o) { take_options(options, o); }, out);
  // What is left is another method's or nobody's.
  for (const auto& item : options) {
    const std::string name = py::str(item.first);
    for_each_method([&](const std::string& other, const auto& table) {
      for (const auto& option : table)
        if (other != method && api_name(option.name) == name)
          usage(name + " applies to method '" + other + "' only, not to method '" + method + "'");
    });
    usage(unknown_option(name));
  }
  return out;
}

// One option as option_specs() lists it (lib/python/README.md).
template <class Options>
py::dict option_spec(const Option<Options>& option, const std::string& method) {
  const Options defaults{};
  py::dict spec;
  spec["name"] = api_name(option.name);
  spec["option"] = "--" + option.name;
  spec["method"] = method.empty() ? py::object(py::none()) : py::object(py::str(method));
  spec["research"] = option.research;
  // The word option and word this one needs ([name, word], the API's names), or None.
  spec["needs"] = option.needs_option
                      ? py::object(py::make_tuple(api_name(option.needs_option), option.needs_word))
                      : py::object(py::none());
  std::visit(
      [&](const auto& value) {
        if constexpr (requires { value.member; }) {
          using T = std::decay_t<decltype(defaults.*value.member)>;
          spec["type"] = std::is_same_v<T, double> ? "float" : "int";
          spec["default"] = defaults.*value.member;
          spec["min"] = value.low;
          spec["max"] = value.high;
        } else {
          spec["type"] = "word";
          spec["default"] = value.get(defaults);
          spec["words"] = value.words;
          // The words naming values of their own (not another spelling): what a menu offers.
          py::list choices;
          for (const std::string& word : value.words) {
            Options chosen = defaults;
            value.set(chosen, word);
            if (value.get(chosen) == word) choices.append(word);
          }
          spec["choices"] = choices;
        }
      },
      option.value);
  spec["help"] = option.help;
  return spec;
}

// Every option the module takes: the run's (method, strength), then each method's.
py::list option_specs() {
  py::list specs;
  for (const Option<RunOptions>& option : option_table<RunOptions>())
    specs.append(option_spec(option, ""));
  for_each_method([&](const std::string& method, const auto& table) {
    for (const auto& option : table) specs.append(option_spec(option, method));
  });
  return specs;
}

// ---- Reports ----------------------------------------------------------------------------------

py::dict figures_dict(const Figures& figures) {
  py::dict d;
  for (const Figure& f : figures)
    std::visit([&](const auto& v) { d[f.key.c_str()] = py::cast(v); }, f.value);
  return d;
}

// The frame's report: per patch its figures (the --report JSON's), and the totals.
py::dict frame_report(const std::vector<PatchFrameReport>& patches, bool edge_spread) {
  py::list list;
  long long moved = 0;
  double max_slide = 0;
  for (const PatchFrameReport& r : patches) {
    Figures figures = frame_figures(r);
    if (!edge_spread)  // not computed
      std::erase_if(figures, [](const Figure& f) { return f.key.starts_with("spread_"); });
    list.append(figures_dict(figures));
    moved += r.moved;
    max_slide = std::max(max_slide, r.max_slide);
  }
  py::dict d;
  d["patches"] = list;
  d["moved"] = moved;
  d["max_slide"] = max_slide;
  return d;
}

// ---- The slider -------------------------------------------------------------------------------

// A bind set-up, built once, immutable, slid from any thread.
class Slider {
 public:
  Slider(const py::handle& bind, const py::handle& faces, const py::handle& patches,
         const std::string& method, const py::object& pins, const py::object& weights,
         double strength, const py::object& corners, const py::object& outer_loop_vertices,
         const py::object& face_sizes, unsigned threads, const py::kwargs& options) {
    const DoubleArray positions = points(bind, "bind");
    std::vector<Index> face_vertices, sizes;
    read_faces(faces, face_sizes, face_vertices, sizes);
    const std::vector<std::vector<Index>> selections = read_patches(patches);
    const SlideOptions slide = slide_options(method, py::dict(options));
    SlideControls controls;
    if (!pins.is_none()) controls.pins = indices(pins, "pins");
    if (!weights.is_none()) {
      const DoubleArray w = DoubleArray::ensure(weights);
      if (!w || w.ndim() != 1) usage("weights must be a 1-D array, one weight a vertex");
      controls.weight.assign(w.data(), w.data() + w.size());
    }
    controls.strength = strength;
    if (!corners.is_none())
      for (const py::handle c : corners) {
        const std::vector<Index> four = indices(c, "each corners entry");
        if (four.size() != 4) usage("each corners entry must name four vertex ids");
        controls.corners.push_back({four[0], four[1], four[2], four[3]});
      }
    if (!outer_loop_vertices.is_none())
      controls.outer_loop_vertices = indices(outer_loop_vertices, "outer_loop_vertices");
    const Bind arrays{
        {positions.data(), static_cast<size_t>(positions.size())}, face_vertices, sizes};
    py::gil_scoped_release released;
    setup_ = std::make_shared<const BindSetup>(
        set_up(arrays, selections, slide, controls, std::max(threads, 1u)));
  }

  py::tuple slide(const py::handle& frame, bool edge_spread) const {
    const DoubleArray in = points(frame, "frame");
    DoubleArray out({static_cast<py::ssize_t>(in.shape(0)), py::ssize_t{3}});
    const std::span<const double> xyz(in.data(), static_cast<size_t>(in.size()));
    const std::span<double> result(out.mutable_data(), static_cast<size_t>(out.size()));
    std::vector<PatchFrameReport> report;
    {
      py::gil_scoped_release released;
      report = skinslide::slide(*setup_, xyz, result, edge_spread);
    }
    return py::make_tuple(out, frame_report(report, edge_spread));
  }

  // A sequence's frames, each (vertices, 3); with a window, each written at the mean of its own
  // and its neighbours' relaxations (skinslide.h slide_sequence).
  py::tuple slide_sequence(const py::handle& frames, int window, const std::string& window_ends,
                           bool edge_spread, unsigned threads) const {
    const WindowEnds ends = window_ends_named(window_ends);  // as the command line reads it
    std::vector<DoubleArray> in;
    for (const py::handle f : frames) in.push_back(points(f, "each frame"));
    const auto count = static_cast<py::ssize_t>(in.size());
    const auto vertices = static_cast<py::ssize_t>(setup_->vertex_count);
    DoubleArray out({count, vertices, py::ssize_t{3}});
    std::vector<std::span<const double>> xyz;
    std::vector<std::span<double>> result;
    for (py::ssize_t k = 0; k < count; ++k) {
      xyz.emplace_back(in[k].data(), static_cast<size_t>(in[k].size()));
      result.emplace_back(out.mutable_data(k), static_cast<size_t>(vertices * 3));
    }
    std::vector<std::vector<PatchFrameReport>> reports;
    {
      py::gil_scoped_release released;
      reports = skinslide::slide_sequence(*setup_, xyz, result, window, edge_spread, threads, ends);
    }
    py::list list;
    for (const auto& r : reports) list.append(frame_report(r, edge_spread));
    return py::make_tuple(out, list);
  }

  Index vertex_count() const { return setup_->vertex_count; }
  std::string method() const { return method_name(method_options(setup_->method)); }
  py::dict options() const { return figures_dict(option_figures(setup_->method)); }
  py::list patches() const {
    py::list list;
    for (size_t p = 0; p < setup_->patches.size(); ++p)
      list.append(figures_dict(patch_figures(setup_->method, p, setup_->patches[p])));
    return list;
  }

 private:
  std::shared_ptr<const BindSetup> setup_;
};

// ---- File formats -----------------------------------------------------------------------------

py::tuple read_mesh(const std::string& path, const std::string& mesh,
                    const std::vector<std::string>& allow_uri_outside) {
  MeshFile file;
  {
    py::gil_scoped_release released;
    file = read_mesh_file(path, {mesh, allow_uri_outside});
  }
  const PolyMesh& m = file.mesh;
  DoubleArray positions({static_cast<py::ssize_t>(m.vertex_count()), py::ssize_t{3}});
  double* p = positions.mutable_data();
  for (const Vec3& v : m.positions) p = std::copy(v.data(), v.data() + 3, p);
  IndexArray sizes(static_cast<py::ssize_t>(m.face_count()));
  for (Index f = 0; f < m.face_count(); ++f) sizes.mutable_data()[f] = m.face_size(f);
  IndexArray face_vertices(static_cast<py::ssize_t>(m.face_vertices.size()));
  std::copy(m.face_vertices.begin(), m.face_vertices.end(), face_vertices.mutable_data());
  return py::make_tuple(positions, face_vertices, sizes);
}

IndexArray index_array(const std::vector<Index>& ids) {
  IndexArray a(static_cast<py::ssize_t>(ids.size()));
  std::copy(ids.begin(), ids.end(), a.mutable_data());
  return a;
}

constexpr Index kNoLimit = INT32_MAX;  // ids checked against nothing but Index's own range

}  // namespace

PYBIND11_MODULE(skinslide, m) {
  m.doc() = "skin sliding for deformed character meshes (lib/python/README.md)";
  m.attr("__version__") = version();
  add_errors(m);
  add_cache_functions(m);  // write_cache, read_cache (cache_module.cpp)
  py::class_<Slider>(m, "Slider",
                     "A bind set-up: Slider(bind, faces, patches, *, method='elastic', pins=None, "
                     "weights=None, strength=1.0, corners=None, outer_loop_vertices=None, "
                     "face_sizes=None, threads=1, **options); slide(frame) -> (positions, "
                     "report).")
      .def(py::init<const py::handle&, const py::handle&, const py::handle&, const std::string&,
                    const py::object&, const py::object&, double, const py::object&,
                    const py::object&, const py::object&, unsigned, const py::kwargs&>(),
           py::arg("bind"), py::arg("faces"), py::arg("patches"), py::kw_only(),
           py::arg("method") = method_name(SlideOptions{}), py::arg("pins") = py::none(),
           py::arg("weights") = py::none(), py::arg("strength") = SlideControls{}.strength,
           py::arg("corners") = py::none(), py::arg("outer_loop_vertices") = py::none(),
           py::arg("face_sizes") = py::none(), py::arg("threads") = 1u)
      .def("slide", &Slider::slide, py::arg("frame"), py::kw_only(), py::arg("edge_spread") = false,
           "Slides one frame ((vertices, 3) float64): returns (positions, report). Releases "
           "the GIL: frames may be slid from several threads at once. edge_spread: report each "
           "patch's edge-length spread in the frame and slid (about 5% more time).")
      .def("slide_sequence", &Slider::slide_sequence, py::arg("frames"), py::kw_only(),
           py::arg("window") = RunOptions{}.window,
           py::arg("window_ends") = window_ends_name(RunOptions{}.window_ends),
           py::arg("edge_spread") = false, py::arg("threads") = 1u,
           "Slides a sequence of frames (each (vertices, 3)): returns (positions (frames, "
           "vertices, 3), reports). window N (elastic): each frame written at the mean of its "
           "own and its N neighbours' slides on each side, as the command line's --window; 0: "
           "each frame slide()'s. window_ends 'cycle': the sequence is a loop, the windows wrap "
           "around (--window-ends). threads: frames slid at once (the same bits for any count). "
           "Releases the GIL.")
      .def_property_readonly("vertex_count", &Slider::vertex_count)
      .def_property_readonly("method", &Slider::method)
      .def_property_readonly("options", &Slider::options)
      .def_property_readonly("patches", &Slider::patches);
  m.def(
      "default_options",
      [](const std::string& method) {
        return figures_dict(option_figures(method_setup(parse_method(method), 0)));
      },
      py::arg("method") = method_name(SlideOptions{}),
      "The method's options with their defaults, as Slider takes them (and 'method').");
  m.def(
      "sequence_option_specs",
      [] {
        py::list specs;
        for (const auto* option : {&window_option(), &window_ends_option()})
          specs.append(option_spec(*option, method_name(ElasticOptions{})));
        return specs;
      },
      "The options slide_sequence takes (window, window_ends), declared as option_specs() "
      "declares the Slider's: the command line's --window and --window-ends.");
  m.def("option_specs", &option_specs,
        "Every option Slider takes, as the command line declares it: a dict each with name, "
        "option (the command line's), method (None: either), type ('int', 'float' or 'word'), "
        "default, min and max (numbers), words and choices (words; choices without other "
        "spellings), help.");
  m.def("read_mesh", &read_mesh, py::arg("path"), py::arg("mesh") = "", py::kw_only(),
        py::arg("allow_uri_outside") = std::vector<std::string>{},
        "Reads an .obj, .gltf or .glb mesh: (positions (V, 3), face_vertices, face_sizes), ids "
        "as skinslide numbers them (glTF: welded vertices, triangles in primitive order). A "
        "glTF's buffers are read only from data: URIs and from files inside its own folder or "
        "inside one of the allow_uri_outside folders (the command line's --allow-uri-outside).");
  m.def(
      "read_patch",
      [](const std::string& path, std::optional<Index> face_count) {
        return index_array(selected_faces(read_patch(path), face_count.value_or(kNoLimit)));
      },
      py::arg("path"), py::arg("face_count") = py::none(),
      "A patch file's face ids, ascending (checked against face_count when given).");
  m.def(
      "read_weights",
      [](const std::string& path, Index vertex_count) {
        const std::vector<double> w = read_weights(path, vertex_count);
        DoubleArray a(static_cast<py::ssize_t>(w.size()));
        std::copy(w.begin(), w.end(), a.mutable_data());
        return a;
      },
      py::arg("path"), py::arg("vertex_count"), "A slide-weight file: one weight a vertex.");
  m.def(
      "read_pins",
      [](const std::string& path, Index vertex_count) {
        return index_array(read_vertex_list(path, vertex_count));
      },
      py::arg("path"), py::arg("vertex_count"), "A pin (vertex-id list) file's ids, ascending.");
}
