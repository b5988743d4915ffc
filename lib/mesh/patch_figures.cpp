#include "mesh/patch_figures.h"

namespace skinslide {
namespace {

long long count(std::size_t n) { return static_cast<long long>(n); }

}  // namespace

Figures patch_counts(const Patch& p) {
  return {{"faces", count(p.faces.size())},
          {"vertices", count(p.vertices.size())},
          {"free", count(p.free_vertices.size())},
          {"pinned", count(p.pinned.size())}};
}

Figures patch_loops(const Patch& p) {
  return {{"loops", count(p.loops.size())},
          {"outer_loop_start", static_cast<long long>(p.vertices[p.loops[p.outer_loop].front()])},
          {"outer_loop_chosen", p.outer_loop_chosen}};
}

}  // namespace skinslide
