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

// A component with L boundary loops is a disk with L - 1 holes exactly when its Euler
// characteristic V - E + F is 2 - L; each handle lowers it by 2. Both methods chart a patch as a
// disk: a handle (a torso with both arms, a whole ear through its helix) cannot be flattened.
void require_disk_with_holes(const PolyMesh& mesh, const PatchComponent& comp,
                             const FaceNamer& name_face) {
  long long corners = 0, border = 0;
  for (Index f : comp.faces) corners += mesh.face_size(f);
  for (const std::vector<Index>& loop : comp.loops) border += static_cast<long long>(loop.size());
  const long long edges = (corners + border) / 2;  // inner edges twice, border edges once
  const long long euler = static_cast<long long>(comp.vertices.size()) - edges +
                          static_cast<long long>(comp.faces.size());
  const long long loops = static_cast<long long>(comp.loops.size());
  if (euler == 2 - loops) return;
  throw_patch("the patch component with " + name_face(comp.faces.front()) + " (" +
              std::to_string(comp.faces.size()) + " faces) is not a disk with holes: it has " +
              std::to_string((2 - loops - euler) / 2) + " handle(s) (V - E + F = " +
              std::to_string(euler) + " with " + std::to_string(loops) +
              " boundary loops); cut it into disks, e.g. leave a ring of faces out across each "
              "handle");
}

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

// One selection's faces, their corners (CSR by position in the selection) and half-edges.
struct SelectionEdges {
  const PolyMesh& mesh;
  const std::vector<Index>& faces;
  const FaceNamer& name_face;
  std::vector<Index> corner_start;  ///< #faces + 1
  Index max_vertex = -1;
  std::vector<HalfEdge> he;  ///< sorted by (lo, hi, face, corner)

  Index face_count() const { return static_cast<Index>(faces.size()); }
  Index corners(Index i) const { return corner_start[i + 1] - corner_start[i]; }
  Index corner(Index face, Index slot) const { return corner_start[face] + slot % corners(face); }
};

// The faces' corners, each face checked for a repeated vertex.
void count_corners(SelectionEdges& sel) {
  const Index nf = sel.face_count();
  sel.corner_start.assign(nf + 1, 0);
  for (Index i = 0; i < nf; ++i) {
    const Index f = sel.faces[i];
    const Index* fv = sel.mesh.face_begin(f);
    const Index n = sel.mesh.face_size(f);
    for (Index a = 0; a < n; ++a)
      for (Index b = a + 1; b < n; ++b)
        if (fv[a] == fv[b])
          throw_patch(sel.name_face(f) + " uses vertex " + std::to_string(fv[a]) +
                      " twice (degenerate face)");
    sel.corner_start[i + 1] = sel.corner_start[i] + n;
    for (Index k = 0; k < n; ++k) sel.max_vertex = std::max(sel.max_vertex, fv[k]);
  }
}

// Half-edges sorted by (lo, hi, face, corner): a counting sort by lo, then each vertex's few.
void sort_half_edges(SelectionEdges& sel) {
  const Index nf = sel.face_count();
  std::vector<Index> lo_start(static_cast<size_t>(sel.max_vertex) + 2, 0);
  auto for_each_half_edge = [&](auto&& visit) {
    for (Index i = 0; i < nf; ++i) {
      const Index* fv = sel.mesh.face_begin(sel.faces[i]);
      const Index n = sel.corners(i);
      for (Index k = 0; k < n; ++k) {
        const Index u = fv[k], v = fv[(k + 1) % n];
        visit(HalfEdge{std::min(u, v), std::max(u, v), i, k, u, v});
      }
    }
  };
  for_each_half_edge([&](const HalfEdge& h) { ++lo_start[h.lo + 1]; });
  for (size_t v = 0; v + 1 < lo_start.size(); ++v) lo_start[v + 1] += lo_start[v];
  sel.he.resize(sel.corner_start[nf]);
  std::vector<Index> next(lo_start.begin(), lo_start.end() - 1);
  for_each_half_edge([&](const HalfEdge& h) { sel.he[next[h.lo]++] = h; });
  for (Index v = 0; v <= sel.max_vertex; ++v)
    std::sort(sel.he.begin() + lo_start[v], sel.he.begin() + lo_start[v + 1],
              [](const HalfEdge& a, const HalfEdge& b) {
                return std::tie(a.hi, a.face, a.corner) < std::tie(b.hi, b.face, b.corner);
              });
}

// Across every inner edge: the two faces join one component and their corners at each end join
// one fan. Returns which half-edges are on the boundary (used by one selected face).
std::vector<char> join_across_edges(const SelectionEdges& sel, UnionFind& face_sets,
                                    UnionFind& corner_sets) {
  const std::vector<HalfEdge>& he = sel.he;
  std::vector<char> boundary_edge(he.size(), 0);
  for (size_t s = 0; s < he.size();) {
    size_t e = s;
    while (e < he.size() && he[e].lo == he[s].lo && he[e].hi == he[s].hi) ++e;
    auto edge = [&] {
      return "edge (" + std::to_string(he[s].lo) + ", " + std::to_string(he[s].hi) + ")";
    };
    auto name = [&](size_t k) { return sel.name_face(sel.faces[he[k].face]); };
    if (e - s > 2)
      throw_patch(edge() + " is shared by " + std::to_string(e - s) + " selected faces: " +
                  name(s) + ", " + name(s + 1) + ", " + name(s + 2) + " (non-manifold edge)");
    if (e - s == 1) {
      boundary_edge[s] = 1;
    } else {
      const HalfEdge& a = he[s];
      const HalfEdge& b = he[s + 1];
      if (a.from == b.from)
        throw_patch(name(s) + " and " + name(s + 1) + " traverse " + edge() +
                    " in the same direction: the patch is not consistently oriented "
                    "(a flipped face, or a non-orientable patch such as a Moebius strip)");
      face_sets.join(a.face, b.face);
      // a: from->to at slots (corner, corner+1); b runs to->from at (corner, corner+1).
      corner_sets.join(sel.corner(a.face, a.corner), sel.corner(b.face, b.corner + 1));
      corner_sets.join(sel.corner(a.face, a.corner + 1), sel.corner(b.face, b.corner));
    }
    s = e;
  }
  return boundary_edge;
}

// Fans: every (component, vertex) must have one corner set. The corners are bucketed by vertex
// (a counting sort), then each vertex's few corners sorted by (component, set, face). Fills the
// components' vertices and the vertices' roles.
void collect_vertices(const SelectionEdges& sel, const std::vector<Index>& comp_of_face,
                      UnionFind& corner_sets,
                      const std::vector<std::pair<Index, Index>>& boundary_vertices,
                      Selected& out) {
  struct Fan {
    Index comp, root, face;
    bool operator<(const Fan& o) const {
      return std::tie(comp, root, face) < std::tie(o.comp, o.root, o.face);
    }
  };
  const Index nf = sel.face_count();
  std::vector<Index> fan_start(static_cast<size_t>(sel.max_vertex) + 2, 0);
  for (Index i = 0; i < nf; ++i) {
    const Index* fv = sel.mesh.face_begin(sel.faces[i]);
    for (Index k = 0; k < sel.corners(i); ++k) ++fan_start[fv[k] + 1];
  }
  for (size_t v = 0; v + 1 < fan_start.size(); ++v) fan_start[v + 1] += fan_start[v];
  std::vector<Fan> fans(sel.corner_start[nf]);
  std::vector<Index> next(fan_start.begin(), fan_start.end() - 1);
  for (Index i = 0; i < nf; ++i) {
    const Index* fv = sel.mesh.face_begin(sel.faces[i]);
    for (Index k = 0; k < sel.corners(i); ++k)
      fans[next[fv[k]]++] = {comp_of_face[i], corner_sets.find(sel.corner_start[i] + k),
                             sel.faces[i]};
  }
  for (Index v = 0; v <= sel.max_vertex; ++v) {
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
                    " is non-manifold: the selected faces around it (" + sel.name_face(s->face) +
                    ", ...) form " + std::to_string(nroots) +
                    " separate fans (a bow-tie); select the faces between them or split the patch");
      out.components[s->comp].vertices.push_back(v);
      const bool on_boundary = std::binary_search(
          boundary_vertices.begin(), boundary_vertices.end(), std::make_pair(s->comp, v));
      out.vertex_roles.emplace_back(v, s->comp, on_boundary);
      s = e;
    }
  }
}

Selected split_selection(const PolyMesh& mesh, const std::vector<Index>& faces, Index selection,
                         const FaceNamer& name_face) {
  SelectionEdges sel{mesh, faces, name_face, {}, -1, {}};
  count_corners(sel);
  sort_half_edges(sel);
  const Index nf = sel.face_count();
  UnionFind face_sets(nf);
  UnionFind corner_sets(sel.corner_start[nf]);
  const std::vector<char> boundary_edge = join_across_edges(sel, face_sets, corner_sets);

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
  for (size_t k = 0; k < sel.he.size(); ++k) {
    if (!boundary_edge[k]) continue;
    boundary_vertices.emplace_back(comp_of_face[sel.he[k].face], sel.he[k].lo);
    boundary_vertices.emplace_back(comp_of_face[sel.he[k].face], sel.he[k].hi);
  }
  std::sort(boundary_vertices.begin(), boundary_vertices.end());
  boundary_vertices.erase(std::unique(boundary_vertices.begin(), boundary_vertices.end()),
                          boundary_vertices.end());
  collect_vertices(sel, comp_of_face, corner_sets, boundary_vertices, out);
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
    require_disk_with_holes(mesh, comp, name_face);
  }
  return out;
}

}  // namespace

std::vector<PatchComponent> patch_components(const PolyMesh& mesh,
                                             const std::vector<std::vector<Index>>& selections,
                                             const FaceNamer& name_face,
                                             const SelectionNamer& name_selection) {
  const auto selection = [&](Index s) {
    return name_selection ? name_selection(s) : "patch " + std::to_string(s);
  };
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
      throw_patch(name_face(owner[k].first) + " is selected by " + selection(owner[k - 1].second) +
                  " and by " + selection(owner[k].second) + "; a face belongs to one patch");
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
