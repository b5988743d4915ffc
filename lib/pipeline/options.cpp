#include "pipeline/options.h"

#include "core/error.h"

namespace skinslide {

SlideMethod parse_method(const std::string& name) {
  if (name == "elastic") return SlideMethod::Elastic;
  if (name == "paper") return SlideMethod::Paper;
  throw Error(ErrorKind::Usage, "unknown method '" + name + "' (elastic, paper)");
}

std::string to_string(SlideMethod m) { return m == SlideMethod::Paper ? "paper" : "elastic"; }

Density parse_density(const std::string& name) {
  if (name == "paper") return Density::Paper;
  if (name == "inverse" || name == "length") return Density::Inverse;
  if (name == "uniform") return Density::Uniform;
  throw Error(ErrorKind::Usage, "unknown density '" + name + "' (paper, inverse, length, uniform)");
}

Holes parse_holes(const std::string& name) {
  if (name == "free") return Holes::Free;
  if (name == "fill") return Holes::Fill;
  throw Error(ErrorKind::Usage, "unknown hole mode '" + name + "' (free, fill)");
}

FrameSolver parse_frame_solver(const std::string& name) {
  if (name == "auto") return FrameSolver::Auto;
  if (name == "cholesky") return FrameSolver::Cholesky;
  if (name == "cg") return FrameSolver::Cg;
  if (name == "multigrid") return FrameSolver::Multigrid;
  throw Error(ErrorKind::Usage,
              "unknown frame solver '" + name + "' (auto, cholesky, cg, multigrid)");
}

Locate parse_locate(const std::string& name) {
  if (name == "walk") return Locate::Walk;
  if (name == "image") return Locate::Image;
  throw Error(ErrorKind::Usage, "unknown locate method '" + name + "' (walk, image)");
}

std::string to_string(Density d) {
  switch (d) {
    case Density::Paper:
      return "paper";
    case Density::Inverse:
      return "inverse";
    case Density::Uniform:
      return "uniform";
  }
  return "?";
}

std::string to_string(Holes h) { return h == Holes::Free ? "free" : "fill"; }

std::string to_string(FrameSolver s) {
  switch (s) {
    case FrameSolver::Auto:
      return "auto";
    case FrameSolver::Cholesky:
      return "cholesky";
    case FrameSolver::Cg:
      return "cg";
    case FrameSolver::Multigrid:
      return "multigrid";
  }
  return "?";
}

}  // namespace skinslide

namespace skinslide {
std::string to_string(Locate l) { return l == Locate::Image ? "image" : "walk"; }
}  // namespace skinslide
