#include "mesh/patches.h"

#include <algorithm>
#include <numeric>
#include <tuple>

#include "core/error.h"
#include "mesh/halfedge.h"

namespace skinslide {
namespace {

struct UnionFind {
  std::vector<Index> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  Index find(Index a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

[[noreturn]] void throw_patch(const std::string& what) { throw Error(ErrorKind::Input, what); }

struct HalfEdge {
  Index lo, hi;    // undirected edge, lo < hi
  Index face;      // position of the face in the selection
  Index corner;    // corner slot of the edge's start vertex in the face
  Index from, to;  // mesh vertex ids in the face's direction
};

struct Selected {
  std::vector<PatchComponent> components;
  // (vertex, component within this selection, is_boundary) of every component vertex
  std::vector<std::tuple<Index, Index, bool>> vertex_roles;
};

Selected split_selection(const PolyMesh& mesh, const std::vector<Index>& faces, Index selection,
                         const FaceNamer& name_face) {
  const Index nf = static_cast<Index>(faces.size());
  std::vector<Index> corner_start(nf + 1, 0);
  for (Index i = 0; i < nf; ++i) {
    const Index f = faces[i];
    const Index* fv = mesh.face_begin(f);
    const Index n = mesh.face_size(f);
    for (Index a = 0; a < n; ++a)
      for (Index b = a + 1; b < n; ++b)
        if (fv[a] == fv[b])
          throw_patch(name_face(f) + " uses vertex " + std::to_string(fv[a]) +
                      " twice (degenerate face)");
    corner_start[i + 1] = corner_start[i] + n;
  }
  // Half-edges sorted by (lo, hi, face, corner): a counting sort by lo, then each vertex's few.
  Index max_vertex = -1;
  for (Index i = 0; i < nf; ++i)
    for (Index k = 0; k < corner_start[i + 1] - corner_start[i]; ++k)
      max_vertex = std::max(max_vertex, mesh.face_begin(faces[i])[k]);
  std::vector<Index> lo_start(static_cast<size_t>(max_vertex) + 2, 0);
  auto for_each_half_edge = [&](auto&& visit) {
    for (Index i = 0; i < nf; ++i) {
      const Index* fv = mesh.face_begin(faces[i]);
      const Index n = corner_start[i + 1] - corner_start[i];
      for (Index k = 0; k < n; ++k) {
        const Index u = fv[k], v = fv[(k + 1) % n];
        visit(HalfEdge{std::min(u, v), std::max(u, v), i, k, u, v});
      }
    }
  };
  for_each_half_edge([&](const HalfEdge& h) { ++lo_start[h.lo + 1]; });
  for (size_t v = 0; v + 1 < lo_start.size(); ++v) lo_start[v + 1] += lo_start[v];
  std::vector<HalfEdge> he(corner_start[nf]);
  {
    std::vector<Index> next(lo_start.begin(), lo_start.end() - 1);
    for_each_half_edge([&](const HalfEdge& h) { he[next[h.lo]++] = h; });
  }
  for (Index v = 0; v <= max_vertex; ++v)
    std::sort(he.begin() + lo_start[v], he.begin() + lo_start[v + 1],
              [](const HalfEdge& a, const HalfEdge& b) {
                return std::tie(a.hi, a.face, a.corner) < std::tie(b.hi, b.face, b.corner);
              });

  UnionFind face_sets(nf);
  UnionFind corner_sets(corner_start[nf]);
  std::vector<char> boundary_edge(he.size(), 0);
  auto corner = [&](Index face, Index slot) {
    const Index n = corner_start[face + 1] - corner_start[face];
    return corner_start[face] + slot % n;
  };
  for (size_t s = 0; s < he.size();) {
    size_t e = s;
    while (e < he.size() && he[e].lo == he[s].lo && he[e].hi == he[s].hi) ++e;
    auto edge = [&] {
      return "edge (" + std::to_string(he[s].lo) + ", " + std::to_string(he[s].hi) + ")";
    };
    if (e - s > 2)
      throw_patch(edge() + " is shared by " + std::to_string(e - s) + " selected faces: " +
                  name_face(faces[he[s].face]) + ", " + name_face(faces[he[s + 1].face]) + ", " +
                  name_face(faces[he[s + 2].face]) + " (non-manifold edge)");
    if (e - s == 1) {
      boundary_edge[s] = 1;
    } else {
      const HalfEdge& a = he[s];
      const HalfEdge& b = he[s + 1];
      if (a.from == b.from)
        throw_patch(name_face(faces[a.face]) + " and " + name_face(faces[b.face]) + " traverse " +
                    edge() +
                    " in the same direction: the patch is not consistently oriented "
                    "(a flipped face, or a non-orientable patch such as a Moebius strip)");
      face_sets.join(a.face, b.face);
      // a: from->to at slots (corner, corner+1); b runs to->from at (corner, corner+1).
      corner_sets.join(corner(a.face, a.corner), corner(b.face, b.corner + 1));
      corner_sets.join(corner(a.face, a.corner + 1), corner(b.face, b.corner));
    }
    s = e;
  }

  // Components, numbered by first face.
  std::vector<Index> comp_of_face(nf, -1);
  Index ncomp = 0;
  std::vector<Index> comp_of_root(nf, -1);
  for (Index i = 0; i < nf; ++i) {
    Index& c = comp_of_root[face_sets.find(i)];
    if (c < 0) c = ncomp++;
    comp_of_face[i] = c;
  }

  Selected out;
  out.components.resize(ncomp);
  for (Index i = 0; i < nf; ++i) out.components[comp_of_face[i]].faces.push_back(faces[i]);
  std::vector<std::pair<Index, Index>> boundary_vertices;  // (comp, vertex)
  for (size_t k = 0; k < he.size(); ++k) {
    if (!boundary_edge[k]) continue;
    boundary_vertices.emplace_back(comp_of_face[he[k].face], he[k].lo);
    boundary_vertices.emplace_back(comp_of_face[he[k].face], he[k].hi);
  }
  std::sort(boundary_vertices.begin(), boundary_vertices.end());
  boundary_vertices.erase(std::unique(boundary_vertices.begin(), boundary_vertices.end()),
                          boundary_vertices.end());
  // Fans: every (component, vertex) must have one corner set. The corners are bucketed by vertex
  // (a counting sort), then each vertex's few corners sorted by (component, set, face).
  struct Fan {
    Index comp, root, face;
    bool operator<(const Fan& o) const {
      return std::tie(comp, root, face) < std::tie(o.comp, o.root, o.face);
    }
  };
  std::vector<Index> fan_start(static_cast<size_t>(max_vertex) + 2, 0);
  for (Index i = 0; i < nf; ++i) {
    const Index* fv = mesh.face_begin(faces[i]);
    for (Index k = 0; k < corner_start[i + 1] - corner_start[i]; ++k) ++fan_start[fv[k] + 1];
  }
  for (size_t v = 0; v + 1 < fan_start.size(); ++v) fan_start[v + 1] += fan_start[v];
  std::vector<Fan> fans(corner_start[nf]);
  {
    std::vector<Index> next(fan_start.begin(), fan_start.end() - 1);
    for (Index i = 0; i < nf; ++i) {
      const Index* fv = mesh.face_begin(faces[i]);
      for (Index k = 0; k < corner_start[i + 1] - corner_start[i]; ++k)
        fans[next[fv[k]]++] = {comp_of_face[i], corner_sets.find(corner_start[i] + k), faces[i]};
    }
  }
  for (Index v = 0; v <= max_vertex; ++v) {
    const auto begin = fans.begin() + fan_start[v], end = fans.begin() + fan_start[v + 1];
    std::sort(begin, end);
    for (auto s = begin; s != end;) {
      auto e = s;
      Index nroots = 0;
      Index last_root = -1;
      while (e != end && e->comp == s->comp) {
        if (e->root != last_root) {
          ++nroots;
          last_root = e->root;
        }
        ++e;
      }
      if (nroots > 1)
        throw_patch("vertex " + std::to_string(v) +
                    " is non-manifold: the selected faces around it (" + name_face(s->face) +
                    ", ...) form " + std::to_string(nroots) +
                    " separate fans (a bow-tie); select the faces between them or split the patch");
      out.components[s->comp].vertices.push_back(v);
      const bool on_boundary = std::binary_search(
          boundary_vertices.begin(), boundary_vertices.end(), std::make_pair(s->comp, v));
      out.vertex_roles.emplace_back(v, s->comp, on_boundary);
      s = e;
    }
  }
  for (Index c = 0; c < ncomp; ++c) {
    PatchComponent& comp = out.components[c];
    comp.selection = selection;
    const bool has_boundary = std::any_of(boundary_vertices.begin(), boundary_vertices.end(),
                                          [&](const auto& bv) { return bv.first == c; });
    if (!has_boundary)
      throw_patch("the patch component with " + name_face(comp.faces.front()) + " (" +
                  std::to_string(comp.faces.size()) +
                  " faces) has no boundary: it is a closed surface; leave at least one face out");
    comp.loops = boundary_loops(mesh, comp.faces);
  }
  return out;
}

}  // namespace

std::vector<PatchComponent> patch_components(const PolyMesh& mesh,
                                             const std::vector<std::vector<Index>>& selections,
                                             const FaceNamer& name_face) {
  std::vector<PatchComponent> all;
  std::vector<std::tuple<Index, Index, bool>> roles;  // vertex, global component, boundary
  std::vector<std::pair<Index, Index>> owner;         // face, selection
  for (Index s = 0; s < static_cast<Index>(selections.size()); ++s) {
    for (Index f : selections[s]) owner.emplace_back(f, s);
    Selected sel = split_selection(mesh, selections[s], s, name_face);
    const Index base = static_cast<Index>(all.size());
    for (auto& [v, c, b] : sel.vertex_roles) roles.emplace_back(v, base + c, b);
    for (auto& c : sel.components) all.push_back(std::move(c));
  }
  std::sort(owner.begin(), owner.end());
  for (size_t k = 1; k < owner.size(); ++k)
    if (owner[k].first == owner[k - 1].first)
      throw_patch(name_face(owner[k].first) + " is selected by patch " +
                  std::to_string(owner[k - 1].second) + " and by patch " +
                  std::to_string(owner[k].second) + "; a face belongs to one patch");
  std::sort(roles.begin(), roles.end());
  for (size_t s = 0; s < roles.size();) {
    size_t e = s;
    while (e < roles.size() && std::get<0>(roles[e]) == std::get<0>(roles[s])) ++e;
    if (e - s > 1)
      for (size_t k = s; k < e; ++k)
        if (!std::get<2>(roles[k]))
          throw_patch("vertex " + std::to_string(std::get<0>(roles[s])) +
                      " is inside one patch component (" +
                      name_face(all[std::get<1>(roles[k])].faces.front()) +
                      ") and also touches another: patches may share only boundary vertices");
    s = e;
  }
  std::stable_sort(all.begin(), all.end(), [](const PatchComponent& a, const PatchComponent& b) {
    return std::tie(a.vertices.front(), a.faces.front()) <
           std::tie(b.vertices.front(), b.faces.front());
  });
  return all;
}

}  // namespace skinslide
