#include "mesh/halfedge.h"

#include <algorithm>
#include <string>

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include "core/check.h"

namespace skinslide {
namespace {
struct Traits : OpenMesh::DefaultTraits {};
using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<Traits>;
}  // namespace

std::vector<std::vector<Index>> boundary_loops(const PolyMesh& mesh,
                                               const std::vector<Index>& faces) {
  // Local vertex ids: the sorted mesh ids of the faces' vertices.
  std::vector<Index> verts;
  size_t corners = 0;
  for (Index f : faces) {
    verts.insert(verts.end(), mesh.face_begin(f), mesh.face_begin(f) + mesh.face_size(f));
    corners += static_cast<size_t>(mesh.face_size(f));
  }
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  std::vector<int> local(verts.empty() ? 0 : static_cast<size_t>(verts.back()) + 1, -1);
  for (size_t i = 0; i < verts.size(); ++i) local[verts[i]] = static_cast<int>(i);

  OmMesh om;
  // Edges: about half the corners plus half the border; reserving avoids regrowing the arrays.
  om.reserve(verts.size(), corners / 2 + verts.size() / 8, faces.size());
  std::vector<OmMesh::VertexHandle> vh;
  vh.reserve(verts.size());
  for (size_t i = 0; i < verts.size(); ++i) vh.push_back(om.add_vertex(OmMesh::Point(0, 0, 0)));
  std::vector<OmMesh::VertexHandle> fv;
  for (Index f : faces) {
    fv.clear();
    for (Index k = 0; k < mesh.face_size(f); ++k) fv.push_back(vh[local[mesh.face_begin(f)[k]]]);
    const auto fh = om.add_face(fv);
    SKINSLIDE_CHECK(fh.is_valid(), "OpenMesh refused face " + std::to_string(f));
  }

  std::vector<std::vector<Index>> loops;
  std::vector<char> seen(om.n_halfedges(), 0);
  for (auto he : om.halfedges()) {
    if (!om.is_boundary(he) || seen[he.idx()]) continue;
    // OpenMesh's boundary halfedges run against the faces' direction: collect, then reverse.
    std::vector<Index> loop;
    auto h = he;
    do {
      seen[h.idx()] = 1;
      loop.push_back(verts[om.from_vertex_handle(h).idx()]);
      h = om.next_halfedge_handle(h);
      SKINSLIDE_CHECK(loop.size() <= verts.size(), "boundary loop does not close");
    } while (h != he);
    std::reverse(loop.begin(), loop.end());
    std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
    loops.push_back(std::move(loop));
  }
  std::sort(loops.begin(), loops.end(),
            [](const auto& a, const auto& b) { return a.front() < b.front(); });
  return loops;
}

}  // namespace skinslide
