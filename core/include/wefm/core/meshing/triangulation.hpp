#pragma once
// Constrained Delaunay triangulation of a UV domain (METHOD §9.2, free meshing): incremental
// Bowyer-Watson insertion inside a super-triangle, segments recovered by edge flips (Sloan), the
// outside and the holes removed by parity across the segments; then insertion by a refinement
// strategy (frontal.cpp, or the circumcentre refinement here). All topological decisions go
// through the robust predicates.
#include <array>
#include <cstdint>
#include <functional>
#include <set>
#include <utility>
#include <vector>

#include "wefm/core/meshing/predicates.hpp"

namespace wefm::meshing {

class Triangulation {
 public:
  // Boundary nodes and the segments joining them (closed loops). A segment given both ways (a, b)
  // and (b, a) is a scar: the boundary runs along both of its sides, so it is an edge of the mesh
  // with the domain on both sides (a seam kept closed, a hard edge inside a face). Throws
  // Error(invalid_state) when the boundary touches itself otherwise (two nodes at one point, a node
  // on another segment) and Error(internal) if a segment still cannot be recovered.
  Triangulation(const std::vector<P2>& points, const std::vector<std::array<Index, 2>>& segments);

  // Node numbers are the caller's: 0..points.size()-1 the boundary, then inserted nodes. `hint`
  // is a triangle slot to start the search from (any value works).
  // Inserts p unless it lies outside, on a segment, or closer than half its length to a segment it
  // can see; then `encroached` (if given) gets that segment's two nodes. Returns the new node or -1.
  // `near_ok`, if given, is asked about every node the new one would be joined to and can refuse
  // the insertion (a point too close to a node, judged in 3D by the caller).
  Index insert(const P2& p, Index hint, std::array<Index, 2>* encroached = nullptr,
               const std::function<bool(Index)>* near_ok = nullptr);

  // Refinement: `size(a, b, c)` (nodes) says +1 too big (always refined), 0 fine (refined when an
  // angle in UV is below `min_angle_rad`) or -1 too small to refine at all, which bounds the
  // cascades a small angle at the boundary would start; smoothing takes over there.
  // Circumcentres that encroach a segment are replaced by the apex of the equilateral
  // triangle on it (segments are never split: their nodes are the boundary discretisation).
  void refine(const std::function<int(Index, Index, Index)>& size, double min_angle_rad, std::int64_t max_nodes,
              const std::function<void(Index)>& on_insert);

  // Read access for refinement strategies outside this class (frontal.cpp). Triangle slots are
  // reused after a deletion; `generation` changes whenever a slot's triangle does, so a queued
  // (slot, generation) pair tells a stale entry from a live one. Corners are in the caller's node
  // numbering, counter-clockwise; corner i faces edge i, whose neighbour is `neighbour(t, i)`.
  Index slot_count() const { return static_cast<Index>(tris_.size()); }
  bool live(Index t) const { return tris_[static_cast<size_t>(t)].live; }
  bool inside(Index t) const { return tris_[static_cast<size_t>(t)].inside; }
  std::uint32_t generation(Index t) const { return tris_[static_cast<size_t>(t)].gen; }
  Index corner(Index t, int i) const { return tris_[static_cast<size_t>(t)].v[static_cast<size_t>(i)] - 3; }
  Index neighbour(Index t, int i) const { return tris_[static_cast<size_t>(t)].n[static_cast<size_t>(i)]; }
  bool constrained(Index t, int i) const { return tris_[static_cast<size_t>(t)].c[static_cast<size_t>(i)]; }
  std::vector<Index> triangles_around(Index node) const { return star(node + 3); }

  // Structural check for tests: neighbour links reciprocal, every live triangle positive.
  bool valid() const;

  Index node_count() const { return static_cast<Index>(pts_.size()) - 3; }
  const P2& node(Index i) const { return pts_[static_cast<size_t>(i) + 3]; }
  // Inside triangles as node triples (counter-clockwise), super-triangle nodes excluded.
  std::vector<std::array<Index, 3>> triangles() const;

 private:
  struct T {
    std::array<Index, 3> v{}, n{{-1, -1, -1}};
    std::array<bool, 3> c{{false, false, false}};
    bool live = true, inside = true;
    std::uint32_t gen = 0;
  };
  Index locate(const P2& p, Index hint, bool stop_at_segments, std::array<Index, 2>* crossed) const;
  // insert for internal node v, whose point is already in pts_: its cavity and the triangles on its rim.
  Index place(Index v, Index hint, std::array<Index, 2>* encroached, const std::function<bool(Index)>* near_ok);
  void flip(Index t, int i);
  void link(Index t, int i, Index s);
  Index edge_triangle(Index a, Index b, int* i) const;  // triangle with directed edge a->b
  Index edge_triangle_in_star(Index a, Index b, int* i) const;  // the same, searched in star(a)
  std::vector<Index> star(Index a) const;               // live triangles around internal node a
  void recover(Index a, Index b);
  void mark_inside();
  void renumber_slots();  // live triangles only, in the order of their sorted corners
  Index new_tri(Index a, Index b, Index c);

  std::vector<P2> pts_;  // the super-triangle nodes first (0..2), then the caller's nodes
  std::vector<T> tris_;
  std::vector<Index> vtri_;  // a live triangle per node
  std::vector<Index> free_;
  Index last_ = 0;
  std::vector<char> mark_;
  // insert's working lists, kept between calls so that each insertion does not allocate them.
  struct Rim {
    Index a, b, out;
    bool c;
  };
  std::vector<Index> cav_, made_;
  std::vector<Rim> rim_;
  std::set<std::pair<Index, Index>> scars_;  // internal node pairs (smaller first) of scar segments
};

}  // namespace wefm::meshing
