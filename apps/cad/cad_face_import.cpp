// Face import. OCCT's triangulation of a face lives in the face's parameter space, so it is cut open
// where the parameterisation is: a seam edge (closed on the face) has two node chains, one per side,
// and a degenerate edge (sphere pole, cone apex) has a chain of distinct nodes at one 3D point. The
// flattener wants the face as it is in 3D: both sides of a seam merged into one repeated edge (used
// twice by the loop, once each way) and a degenerate edge merged into one vertex. We merge exactly
// the nodes the topology says are the same (the two sides of a seam pairwise, all nodes of a
// degenerate edge) rather than welding by distance, so distinct nodes that happen to be close (needle
// triangles) are never merged. Triangles that collapse in the merge (at a pole) are dropped. The one
// merge by distance is of a node on no edge at the very point of a node it shares a facet with
// (merge_duplicate_inside_nodes): a duplicate, with zero-area facets between the two.
#include "cad_face_import.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include <BRepAdaptor_Curve.hxx>
#include <BRepCheck.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Result.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <Geom2d_Curve.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec.hxx>

#include "cad_face_repair.hpp"
#include "cad_polygon_fill.hpp"

namespace wefm_cad {

namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(static_cast<size_t>(n)) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int a) {
    while (parent[static_cast<size_t>(a)] != a) a = parent[static_cast<size_t>(a)] = parent[static_cast<size_t>(parent[static_cast<size_t>(a)])];
    return a;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
  }
};

const char* curve_type_name(GeomAbs_CurveType t) {
  switch (t) {
    case GeomAbs_Line: return "Line";
    case GeomAbs_Circle: return "Circle";
    case GeomAbs_Ellipse: return "Ellipse";
    case GeomAbs_Hyperbola: return "Hyperbola";
    case GeomAbs_Parabola: return "Parabola";
    case GeomAbs_BezierCurve: return "BezierCurve";
    case GeomAbs_BSplineCurve: return "BSplineCurve";
    case GeomAbs_OffsetCurve: return "OffsetCurve";
    default: return "OtherCurve";
  }
}

// 0-based node indices of an edge's polygon on the face triangulation (empty if there is none).
std::vector<int> polygon_nodes(const TopoDS_Edge& edge, const Handle(Poly_Triangulation)& tri, const TopLoc_Location& loc) {
  std::vector<int> nodes;
  const Handle(Poly_PolygonOnTriangulation)& poly = BRep_Tool::PolygonOnTriangulation(edge, tri, loc);
  if (poly.IsNull()) return nodes;
  for (int i = 1; i <= poly->NbNodes(); ++i) nodes.push_back(poly->Node(i) - 1);
  return nodes;
}

// The edges of a wire in walking order, oriented (face orientation composed in). WireExplorer orders
// them by connectivity; it can skip edges of odd wires, in which case we keep the stored order and let
// the library's loop validation speak.
std::vector<TopoDS_Edge> wire_edges(const TopoDS_Wire& wire, const TopoDS_Face& face) {
  std::vector<TopoDS_Edge> ordered, stored;
  for (BRepTools_WireExplorer ex(wire, face); ex.More(); ex.Next()) ordered.push_back(ex.Current());
  for (TopExp_Explorer ex(wire, TopAbs_EDGE); ex.More(); ex.Next()) stored.push_back(TopoDS::Edge(ex.Current()));
  return ordered.size() == stored.size() ? ordered : stored;
}

// The largest part of a seam's length that close_lost_tips merges into its pole: ellipsoids 20 and
// 50 times longer than wide lose 0.3 % and 2.1 % of it.
constexpr double kLostTipShare = 0.1;

// Twice a triangle's area over its longest edge squared, below which it is a sliver folded flat (its
// smallest angle under about 0.06 degrees).
constexpr double kFoldedArea = 1e-3;

class Importer {
 public:
  // An INTERNAL or EXTERNAL face (a sheet inside or beside a solid) hands that orientation down to
  // its wires and edges, which would then read as constraint lines and leave the face without a
  // boundary: it is imported as FORWARD.
  Importer(const TopoDS_Face& face, const TopTools_IndexedMapOfShape& edges, CadFace& out)
      : face_(face.Orientation() == TopAbs_INTERNAL || face.Orientation() == TopAbs_EXTERNAL
                  ? TopoDS::Face(face.Oriented(TopAbs_FORWARD))
                  : face),
        edge_map_(edges),
        out_(out) {}

  bool run() {
    tri_ = BRep_Tool::Triangulation(face_, loc_);
    if (tri_.IsNull() || tri_->NbTriangles() == 0) return from_edge_polygons();
    const gp_Trsf trsf = loc_.Transformation();
    const int n = tri_->NbNodes();
    points_.reserve(static_cast<size_t>(n));
    for (int i = 1; i <= n; ++i) points_.push_back(tri_->Node(i).Transformed(trsf));
    for (int t = 1; t <= tri_->NbTriangles(); ++t) {
      int a = 0, b = 0, c = 0;
      tri_->Triangle(t).Get(a, b, c);
      facets_.push_back({a - 1, b - 1, c - 1});
    }
    UnionFind uf(n);
    if (!collect_loops() || !merge_edges(uf) || !cover_boundary(uf)) return false;
    merge_duplicate_inside_nodes(uf);
    build_mesh(uf);
    return out_.error.empty();
  }

 private:
  bool fail(std::string why) {
    out_.error = std::move(why);
    return false;
  }

  // Loops as (model edge id, oriented edge) uses; the per-face edge list in first-use order.
  bool collect_loops() {
    const TopoDS_Wire outer = BRepTools::OuterWire(face_);
    for (TopExp_Explorer wx(face_, TopAbs_WIRE); wx.More(); wx.Next()) {
      const TopoDS_Wire wire = TopoDS::Wire(wx.Current());
      const bool is_outer = !outer.IsNull() && wire.IsSame(outer);
      std::vector<CadEdgeUse> loop;
      for (const TopoDS_Edge& e : wire_edges(wire, face_)) {
        // INTERNAL/EXTERNAL edges are constraint lines inside (or outside) the face, not its boundary:
        // the triangulation already follows them, so they are no part of a loop.
        if (e.Orientation() == TopAbs_INTERNAL || e.Orientation() == TopAbs_EXTERNAL) continue;
        const int id = edge_map_.FindIndex(e);
        if (id <= 0) return fail("an edge of the face is not in the model's edge map");
        auto [it, fresh] = local_.emplace(id, static_cast<int32_t>(out_.edges.size()));
        if (fresh) {
          CadEdge ce;
          ce.id = id;
          ce.degenerated = BRep_Tool::Degenerated(e);
          ce.seam = BRep_Tool::IsClosed(e, face_);
          ce.curve_type = ce.degenerated ? "Unknown" : curve_type_name(BRepAdaptor_Curve(e).GetType());
          out_.edges.push_back(ce);
          shapes_.push_back(e);
        }
        loop.push_back({it->second, e.Orientation() == TopAbs_REVERSED});
      }
      if (loop.empty()) continue;
      if (is_outer) out_.outer_loop = static_cast<int>(out_.loops.size());
      out_.loops.push_back(std::move(loop));
    }
    if (out_.loops.empty()) return fail("the face has no wire");
    return true;
  }

  // BRepMesh can make no facets for a face (narrower than the deflection, between edges whose
  // polygons cross) while its neighbours have theirs, and so polygons of the shared edges. A face with
  // one loop without seam or pole is then built on those polygons' nodes (so its edges match the
  // neighbours') and filled from its loop in the surface's parameters.
  bool from_edge_polygons() {
    const std::string why = "the face has no triangulation (BRepMesh made none)";
    if (!collect_loops()) return false;
    if (out_.loops.size() != 1) return fail(why + " and more than one loop");
    TopTools_IndexedMapOfShape vertices;
    std::vector<int> vertex_node;
    std::vector<std::array<double, 2>> uv;
    raw_chains_.resize(out_.edges.size());
    for (size_t k = 0; k < out_.edges.size(); ++k) {
      const std::string edge = " and edge " + std::to_string(out_.edges[k].id);
      if (out_.edges[k].seam || out_.edges[k].degenerated) return fail(why + " and a seam or a pole");
      const TopoDS_Edge e = TopoDS::Edge(shapes_[k].Oriented(TopAbs_FORWARD));
      Handle(Poly_PolygonOnTriangulation) poly;
      Handle(Poly_Triangulation) tri;
      TopLoc_Location loc;
      BRep_Tool::PolygonOnTriangulation(e, poly, tri, loc, 1);
      if (poly.IsNull() || tri.IsNull() || !poly->HasParameters() || poly->NbNodes() < 2)
        return fail(why + edge + " has no polygon on another face's facets");
      double first = 0, last = 0;
      const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(e, face_, first, last);
      if (pcurve.IsNull()) return fail(why + edge + " has no curve on the face");
      TopoDS_Vertex ends[2];
      TopExp::Vertices(e, ends[0], ends[1]);
      for (int i = 1; i <= poly->NbNodes(); ++i) {
        const bool end = i == 1 || i == poly->NbNodes();
        if (end && ends[i == 1 ? 0 : 1].IsNull()) return fail(why + edge + " has no vertex");
        const int slot = end ? vertices.Add(ends[i == 1 ? 0 : 1]) : 0;
        if (end && slot <= static_cast<int>(vertex_node.size())) {
          raw_chains_[k].push_back(vertex_node[static_cast<size_t>(slot - 1)]);
          continue;
        }
        const gp_Pnt2d p = pcurve->Value(poly->Parameter(i));
        if (end) vertex_node.push_back(static_cast<int>(points_.size()));
        raw_chains_[k].push_back(static_cast<int>(points_.size()));
        points_.push_back(tri->Node(poly->Node(i)).Transformed(loc.Transformation()));
        uv.push_back({p.X(), p.Y()});
      }
    }
    std::vector<int> ring;
    for (const CadEdgeUse& u : out_.loops.front()) {
      std::vector<int> chain = raw_chains_[static_cast<size_t>(u.edge)];
      if (u.reversed) std::reverse(chain.begin(), chain.end());
      for (int node : chain)
        if (ring.empty() || ring.back() != node) ring.push_back(node);
    }
    if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
    std::vector<std::array<double, 2>> ring_uv;
    for (int node : ring) ring_uv.push_back(uv[static_cast<size_t>(node)]);
    for (const std::array<int, 3>& t : fill_polygon(ring_uv))
      facets_.push_back({ring[static_cast<size_t>(t[0])], ring[static_cast<size_t>(t[1])], ring[static_cast<size_t>(t[2])]});
    if (facets_.empty()) return fail(why + " and its loop has fewer than 3 nodes");
    UnionFind uf(static_cast<int>(points_.size()));
    build_mesh(uf);
    return out_.error.empty();
  }

  // Chains in triangulation node indices; merges seam sides and degenerate points.
  bool merge_edges(UnionFind& uf) {
    raw_chains_.resize(out_.edges.size());
    for (size_t k = 0; k < out_.edges.size(); ++k) {
      CadEdge& ce = out_.edges[k];
      const TopoDS_Edge fwd = TopoDS::Edge(shapes_[k].Oriented(TopAbs_FORWARD));
      std::vector<int> chain = polygon_nodes(fwd, tri_, loc_);
      if (ce.degenerated) {
        if (chain.empty()) chain = nodes_at(BRep_Tool::Pnt(TopExp::FirstVertex(fwd)));
        if (chain.empty()) return fail("degenerate edge " + std::to_string(ce.id) + " has no node on the triangulation");
        for (int v : chain) uf.unite(chain.front(), v);
        raw_chains_[k] = {chain.front()};
        continue;
      }
      if (chain.size() < 2) return fail("edge " + std::to_string(ce.id) + " has no polygon on the face triangulation");
      if (ce.seam) {
        const std::vector<int> other = polygon_nodes(TopoDS::Edge(shapes_[k].Oriented(TopAbs_REVERSED)), tri_, loc_);
        if (other.size() != chain.size())
          return fail("seam edge " + std::to_string(ce.id) + ": its two sides have " + std::to_string(chain.size()) +
                      " and " + std::to_string(other.size()) + " nodes");
        // Both sides are discretised at the same curve parameters, so node i of one side lies on
        // node i of the other. Checked, because merging the wrong nodes would tear the mesh.
        const double tol = 1e-6 * chain_length(chain);
        for (size_t i = 0; i < chain.size(); ++i)
          if (points_[static_cast<size_t>(chain[i])].Distance(points_[static_cast<size_t>(other[i])]) > tol)
            return fail("seam edge " + std::to_string(ce.id) + ": node " + std::to_string(i) +
                        " of its two sides is not at the same 3D point");
        for (size_t i = 0; i < chain.size(); ++i) uf.unite(chain[i], other[i]);
      }
      raw_chains_[k] = chain;
    }
    return true;
  }

  // BRepMesh can leave a node inside a face at the very point of another node, with zero-area
  // facets between them (gmsh_SampleCrankshaft4A's B-spline face 41 at a deflection of 0.0003 of the
  // diagonal: four such pairs, one node of each in no other facet). The lone node then has no facet
  // to predict it, and the flattening refuses the face. A node on no edge's chain is merged into the
  // node it lies on (same_point_tolerance, as a pole's nodes); its zero-area
  // facets collapse and are dropped. Nodes on edge chains are merged by topology only (merge_edges).
  void merge_duplicate_inside_nodes(UnionFind& uf) {
    std::vector<bool> on_chain(points_.size(), false);
    for (const std::vector<int>& chain : raw_chains_)
      for (int v : chain) on_chain[static_cast<size_t>(v)] = true;
    const double tol = same_point_tolerance();
    // Only the facets' own edges: a duplicate shares a zero-area facet with the node it lies on.
    for (const std::array<int, 3>& f : facets_)
      for (size_t c = 0; c < 3; ++c) {
        const int a = f[c], b = f[(c + 1) % 3];
        if (on_chain[static_cast<size_t>(a)] && on_chain[static_cast<size_t>(b)]) continue;
        if (points_[static_cast<size_t>(a)].Distance(points_[static_cast<size_t>(b)]) <= tol) uf.unite(a, b);
      }
  }

  // BRepMesh can give up on a face and leave facets that miss its edges' polygons (one facet among
  // twenty boundary nodes). A face bounded by one loop, without a seam or a pole, is then filled
  // from that loop in the surface's parameters, where BRepMesh's facets turn counter-clockwise.
  bool cover_boundary(UnionFind& uf) {
    std::set<std::pair<int, int>> facet_edges;
    for (const std::array<int, 3>& t : facets_)
      for (size_t c = 0; c < 3; ++c) facet_edges.insert(std::minmax(uf.find(t[c]), uf.find(t[(c + 1) % 3])));
    const CadEdge* missed = nullptr;
    for (size_t k = 0; k < out_.edges.size() && !missed; ++k)
      for (size_t i = 0; i + 1 < raw_chains_[k].size() && !missed; ++i) {
        const int a = uf.find(raw_chains_[k][i]), b = uf.find(raw_chains_[k][i + 1]);
        if (a != b && !facet_edges.count(std::minmax(a, b))) missed = &out_.edges[k];
      }
    if (!missed) return true;
    const std::string why = "BRepMesh's facets miss the polygon of edge " + std::to_string(missed->id);
    if (out_.loops.size() != 1 || !tri_->HasUVNodes()) return fail(why + " and the face has more than one loop");
    std::vector<int> ring;
    for (const CadEdgeUse& u : out_.loops.front()) {
      if (out_.edges[static_cast<size_t>(u.edge)].seam || out_.edges[static_cast<size_t>(u.edge)].degenerated)
        return fail(why + " and the face has a seam or a pole");
      std::vector<int> chain = raw_chains_[static_cast<size_t>(u.edge)];
      if (u.reversed) std::reverse(chain.begin(), chain.end());
      for (int node : chain)
        if (ring.empty() || uf.find(ring.back()) != uf.find(node)) ring.push_back(node);
    }
    if (ring.size() > 1 && uf.find(ring.front()) == uf.find(ring.back())) ring.pop_back();
    std::vector<std::array<double, 2>> uv;
    for (int node : ring) uv.push_back({tri_->UVNode(node + 1).X(), tri_->UVNode(node + 1).Y()});
    const std::vector<std::array<int, 3>> filled = fill_polygon(uv);
    if (filled.empty()) return fail(why + " and its loop has fewer than 3 nodes");
    facets_.clear();
    for (const std::array<int, 3>& t : filled)
      facets_.push_back({ring[static_cast<size_t>(t[0])], ring[static_cast<size_t>(t[1])], ring[static_cast<size_t>(t[2])]});
    return true;
  }

  double chain_length(const std::vector<int>& chain) const {
    double length = 0;
    for (size_t i = 0; i + 1 < chain.size(); ++i)
      length += points_[static_cast<size_t>(chain[i])].Distance(points_[static_cast<size_t>(chain[i + 1])]);
    return length;
  }

  // Two triangulation nodes closer than this are at one point: far below any edge length of the face.
  double same_point_tolerance() const {
    double scale = 0;
    for (const gp_Pnt& q : points_) scale = std::max(scale, q.Distance(points_.front()));
    return 1e-9 * std::max(scale, 1e-300);
  }

  // Triangulation nodes at a 3D point (a degenerate edge without a polygon).
  std::vector<int> nodes_at(const gp_Pnt& p) const {
    const double tol = same_point_tolerance();
    std::vector<int> found;
    for (size_t i = 0; i < points_.size(); ++i)
      if (points_[i].Distance(p) <= tol) found.push_back(static_cast<int>(i));
    return found;
  }

  // BRepMesh can leave, next to a pole or a seam, a sliver folded onto an edge two others already
  // share (an edge of three triangles, which the library refuses). Such a sliver carries next to
  // nothing of the surface: it is dropped. A triangle on an edge of two, or one with a real angle,
  // is never dropped here.
  void drop_slivers_on_overused_edges() {
    auto& t = out_.triangles;
    std::map<std::pair<int32_t, int32_t>, int> uses;
    for (size_t k = 0; k < t.size(); ++k) {
      const size_t base = k - k % 3;
      ++uses[std::minmax(t[k], t[base + (k % 3 + 1) % 3])];
    }
    auto overused = [&](size_t tri) {
      for (size_t c = 0; c < 3; ++c)
        if (uses[std::minmax(t[3 * tri + c], t[3 * tri + (c + 1) % 3])] > 2) return true;
      return false;
    };
    std::vector<int32_t> kept;
    for (size_t tri = 0; 3 * tri < t.size(); ++tri) {
      const double* p[3];
      for (size_t c = 0; c < 3; ++c) p[c] = &out_.xyz[3 * static_cast<size_t>(t[3 * tri + c])];
      const gp_Vec u(p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]), v(p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]);
      const double longest = std::max({u.SquareMagnitude(), v.SquareMagnitude(), (v - u).SquareMagnitude()});
      if (overused(tri) && u.Crossed(v).Magnitude() <= kFoldedArea * longest) {
        for (size_t c = 0; c < 3; ++c) --uses[std::minmax(t[3 * tri + c], t[3 * tri + (c + 1) % 3])];
        ++out_.dropped_triangles;
        continue;
      }
      kept.insert(kept.end(), t.begin() + static_cast<std::ptrdiff_t>(3 * tri), t.begin() + static_cast<std::ptrdiff_t>(3 * tri + 3));
    }
    t = std::move(kept);
  }

  // The facets as corner triples of merged nodes, outward. Facets that collapse in the merge (at a
  // pole or apex) are dropped, and so are facets on the same three corners: two of them facing
  // opposite ways close a pocket of no surface (BRepMesh leaves these beside a pole, where they hang
  // on the rest by the pole alone), two facing the same way are one facet twice.
  std::vector<std::array<int, 3>> merged_facets(UnionFind& uf) {
    const bool flip = face_.Orientation() == TopAbs_REVERSED;
    std::vector<std::array<int, 3>> facets;
    std::map<std::array<int, 3>, std::vector<size_t>> by_corners;
    for (std::array<int, 3> f : facets_) {
      if (flip) std::swap(f[1], f[2]);  // outward: the triangulation follows the surface normal
      const std::array<int, 3> r = {uf.find(f[0]), uf.find(f[1]), uf.find(f[2])};
      if (r[0] == r[1] || r[1] == r[2] || r[0] == r[2]) {
        ++out_.dropped_triangles;
        continue;
      }
      std::array<int, 3> sorted = r;
      std::sort(sorted.begin(), sorted.end());
      by_corners[sorted].push_back(facets.size());
      facets.push_back(r);
    }
    std::vector<bool> keep(facets.size(), true);
    for (const auto& [corners, list] : by_corners) {
      if (list.size() < 2) continue;
      int turn = 0;  // facets one way minus facets the other way
      for (size_t k : list) turn += same_turn(facets[k], facets[list.front()]) ? 1 : -1;
      for (size_t i = 0; i < list.size(); ++i) keep[list[i]] = turn != 0 && i == 0;
    }
    std::vector<std::array<int, 3>> kept;
    for (size_t k = 0; k < facets.size(); ++k) {
      if (keep[k]) kept.push_back(facets[k]);
      else ++out_.dropped_triangles;
    }
    return kept;
  }

  static bool same_turn(const std::array<int, 3>& a, const std::array<int, 3>& b) {
    for (int s = 0; s < 3; ++s)
      if (a[0] == b[static_cast<size_t>(s)] && a[1] == b[static_cast<size_t>((s + 1) % 3)]) return true;
    return false;
  }

  // BRepMesh can mesh the tip of a face next to a pole, where the face is narrower than the
  // deflection (a B-spline ellipsoid 20 times longer than wide), with facets that each span the whole
  // period between the seam's two sides. The seam merge collapses them all; the facets left close the
  // surface just below the tip, and the pole and the seam's last nodes are in no facet. Those nodes
  // are merged into the seam's last node that has facets, which goes to the pole's point: the
  // surface keeps its length, and the tip, a few deflections long, is one cone of facets.
  void close_lost_tips(UnionFind& uf, std::vector<std::array<int, 3>>& facets) {
    std::set<int> used, poles;
    for (const std::array<int, 3>& f : facets) used.insert(f.begin(), f.end());
    for (size_t k = 0; k < out_.edges.size(); ++k)
      if (out_.edges[k].degenerated) poles.insert(uf.find(raw_chains_[k].front()));
    bool merged = false;
    for (size_t k = 0; k < out_.edges.size(); ++k) {
      if (!out_.edges[k].seam) continue;
      std::vector<int> chain = raw_chains_[k];
      for (int end = 0; end < 2; ++end, std::reverse(chain.begin(), chain.end())) {
        const int pole = uf.find(chain.front());
        if (!poles.count(pole) || used.count(pole)) continue;
        size_t j = 0;
        while (j < chain.size() && !used.count(uf.find(chain[j]))) ++j;
        // Facets on none of the seam but its other end, or a tip lost over more than a small part of
        // the seam, are left for the topology check to refuse: moving a node that far would distort.
        if (j + 1 >= chain.size()) continue;
        const std::vector<int> tail(chain.begin(), chain.begin() + static_cast<std::ptrdiff_t>(j + 1));
        if (chain_length(tail) > kLostTipShare * chain_length(chain)) continue;
        const gp_Pnt tip = points_[static_cast<size_t>(pole)];
        for (size_t i = 0; i < j; ++i) uf.unite(chain[i], chain[j]);
        points_[static_cast<size_t>(uf.find(chain[j]))] = tip;
        merged = true;
      }
    }
    if (merged)
      for (std::array<int, 3>& f : facets)
        for (int& node : f) node = uf.find(node);
  }

  void build_mesh(UnionFind& uf) {
    std::vector<int32_t> index(points_.size(), -1);
    auto vertex_of = [&](int node) {
      const int r = uf.find(node);
      int32_t& v = index[static_cast<size_t>(r)];
      if (v < 0) {
        v = static_cast<int32_t>(out_.xyz.size() / 3);
        out_.xyz.insert(out_.xyz.end(), {points_[static_cast<size_t>(r)].X(), points_[static_cast<size_t>(r)].Y(),
                                         points_[static_cast<size_t>(r)].Z()});
      }
      return v;
    };
    std::vector<std::array<int, 3>> facets = merged_facets(uf);
    close_lost_tips(uf, facets);
    for (const std::array<int, 3>& f : facets)
      for (int node : f) out_.triangles.push_back(vertex_of(node));
    drop_slivers_on_overused_edges();
    if (out_.triangles.empty()) {
      fail("no triangle left after merging seam sides and degenerate points");
      return;
    }
    for (size_t k = 0; k < out_.edges.size(); ++k) {
      std::vector<int32_t>& chain = out_.edges[k].vertices;
      for (int node : raw_chains_[k]) {
        const int32_t v = vertex_of(node);
        if (chain.empty() || chain.back() != v) chain.push_back(v);
      }
    }
    split_pinched_vertices(out_);
  }

  const TopoDS_Face face_;
  const TopTools_IndexedMapOfShape& edge_map_;
  CadFace& out_;
  TopLoc_Location loc_;
  Handle(Poly_Triangulation) tri_;
  std::vector<gp_Pnt> points_;
  std::unordered_map<int, int32_t> local_;  // model edge id -> index in out_.edges
  std::vector<TopoDS_Edge> shapes_;         // per face edge, one of its oriented shapes
  std::vector<std::vector<int>> raw_chains_;
  std::vector<std::array<int, 3>> facets_;  // 0-based triangulation nodes, BRepMesh's or filled
};

}  // namespace

std::string surface_type_name(const TopoDS_Face& face) {
  switch (BRepAdaptor_Surface(face, Standard_False).GetType()) {
    case GeomAbs_Plane: return "plane";
    case GeomAbs_Cylinder: return "cylinder";
    case GeomAbs_Cone: return "cone";
    case GeomAbs_Sphere: return "sphere";
    case GeomAbs_Torus: return "torus";
    case GeomAbs_BezierSurface: return "bezier";
    case GeomAbs_BSplineSurface: return "bspline";
    case GeomAbs_SurfaceOfRevolution: return "revolution";
    case GeomAbs_SurfaceOfExtrusion: return "extrusion";
    case GeomAbs_OffsetSurface: return "offset";
    default: return "other";
  }
}

namespace {

// What Open CASCADE's own check finds wrong with the face and its wires and edges, or "" where it
// finds nothing but the tessellation's polygons: a face the import cannot take is often one the
// modelling left invalid (a blend that failed), and the user should hear that before blaming the
// mesher.
std::string invalid_by_check(const TopoDS_Face& face) {
  const BRepCheck_Analyzer check(face, Standard_True);
  if (check.IsValid()) return "";
  std::set<std::string> found;
  auto note = [&](const TopoDS_Shape& shape) {
    const Handle(BRepCheck_Result)& result = check.Result(shape);
    if (result.IsNull()) return;
    for (BRepCheck_ListOfStatus::Iterator it(result->Status()); it.More(); it.Next())
      if (it.Value() != BRepCheck_NoError) {
        std::ostringstream name;
        BRepCheck::Print(it.Value(), name);
        std::string text = name.str();
        while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
        // The tessellation's polygons are BRepMesh's, checked too: not the model's fault.
        if (text.find("Polygon") == std::string::npos && text.find("Triangulation") == std::string::npos) found.insert(text);
      }
  };
  note(face);
  for (TopExp_Explorer e(face, TopAbs_WIRE); e.More(); e.Next()) note(e.Current());
  for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) note(e.Current());
  std::string out;
  for (const std::string& f : found) out += (out.empty() ? "" : ", ") + f;
  return out;
}

}  // namespace

CadFace import_face(const TopoDS_Face& face, const TopTools_IndexedMapOfShape& edges, int index) {
  CadFace out;
  out.index = index;
  try {
    out.surface_type = surface_type_name(face);
    Importer(face, edges, out).run();
  } catch (const Standard_Failure& f) {
    out.error = std::string("Open CASCADE: ") + f.GetMessageString();
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  if (!out.error.empty()) {
    try {
      if (const std::string why = invalid_by_check(face); !why.empty())
        out.error += "; the B-rep face is invalid by Open CASCADE's own check (" + why + ")";
    } catch (const Standard_Failure&) {
    }
  }
  return out;
}

}  // namespace wefm_cad
