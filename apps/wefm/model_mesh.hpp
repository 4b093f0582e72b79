#pragma once
// `wefm mesh-model`: the per-face domain meshes assembled into one surface mesh. Nodes on the
// boundary of a face mesh (model edges, seams, poles) are welded to the nodes at the same 3D point
// that other faces, or the other side of a seam, already contributed: the edge nodes were given to
// every face identically (cad_edge_nodes), so matching nodes coincide. Interior nodes are never
// welded, so two faces that merely come close are not stitched together.
#include <array>
#include <cstdint>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "mesh_formats.hpp"

namespace wefm_cli {

// Points by grid cells of side 8 `tol`: the point within `tol` (per coordinate) of a query, if any.
// The cells live in one open-addressed table, each cell's points in a list in the order they were
// added: a weld looks up every boundary node of every face, so this is on the path of every model.
// A query reads the cells that the box of side 4 `tol` around it meets (twice the reach, so rounding
// of the box's bounds never misses a cell): 1.5 per axis on average, where cells of side `tol` and
// their neighbours were always 3.
class PointGrid {
 public:
  explicit PointGrid(double tol) : tol_(tol > 0 ? tol : 1e-300), cell_(8 * tol_) {}
  void add(const double* p, int32_t id);
  int32_t find(const double* p, const std::vector<double>& xyz) const;  // ids index xyz (3 per id); -1 if none
  double tolerance() const { return tol_; }

 private:
  size_t slot(uint64_t key) const;  // the slot holding `key`, or the empty slot where it would go
  void grow();
  double tol_, cell_;
  std::vector<uint64_t> keys_;     // per slot: a cell's key
  std::vector<int32_t> first_;     // per slot: the cell's first entry, -1 for an empty slot
  std::vector<int32_t> last_;      // per slot: the cell's last entry
  std::vector<int32_t> ids_;       // per entry: the point's id
  std::vector<int32_t> next_;      // per entry: the next entry in its cell, -1 at the end
  size_t cells_ = 0;
};

struct ConformityCounts {
  int64_t edges = 0;
  int64_t open_edges = 0;          // used by one triangle: the model's free edges, or a gap
  int64_t non_manifold_edges = 0;  // used by more than two
  // Against the B-rep: a mesh edge on a model edge should be used once per face use of that edge
  // (one on a shell's free edge, two on a closed solid, more where volumes share it), any other edge
  // exactly twice. What differs is a defect: a crack, a T-junction or a fold.
  int64_t brep_edge_segments = 0;  // mesh edges lying on model edges
  int64_t unexplained_open_edges = 0;          // used fewer times than the B-rep says
  int64_t unexplained_non_manifold_edges = 0;  // used more times than the B-rep says
  int64_t zero_area_triangles = 0;
  std::vector<int> defect_faces;   // faces holding a triangle on an unexplained edge, or a zero-area one
  struct DefectEdge {
    double midpoint[3];
    int uses, expected;
  };
  std::vector<DefectEdge> defect_edges;  // the first few unexplained edges, to find them in the mesh
  bool defects() const { return unexplained_open_edges || unexplained_non_manifold_edges || zero_area_triangles; }
};

struct LambdaStats {
  double lambda_mesh = 0;          // geometric mean of Lo's lambda
  double lambda_min = 0;
  double fraction_below_0_6 = 0;
  int64_t triangles = 0;
};

class ModelMesh {
 public:
  explicit ModelMesh(double weld_tolerance) : grid_(weld_tolerance) {}

  // Adds one face's mesh (3 doubles per node, 3 node indices per triangle). Returns the number of
  // triangles dropped because welding collapsed them (at a pole) or folded two of them onto the same
  // three nodes (near the end of a seam). `triangle_tags` (one per triangle, or empty for face_tag)
  // are the faces the output puts them in: a face meshed for several B-rep faces (virtual_faces)
  // is welded and checked as one face, written as its B-rep faces.
  // `quad_of` (one per triangle, or empty): triangles with the same number >= 0 are the two halves
  // of one quad of the face mesh (quad-dominant and all-quad meshes), listed one after the other;
  // they are split again along the quad's better diagonal after welding (resplit_quad). The file gets
  // the quad where both halves are still there after welding, a triangle where one is left.
  int64_t add_face(int face_tag, const std::vector<double>& xyz, const std::vector<int32_t>& triangles,
                   const std::vector<int>& triangle_tags = {}, const std::vector<int32_t>& quad_of = {});

  // Two faces meeting at a sharp kink of their common edge, or at a corner between two of their
  // common edges, can each close it with the same triangle, once each way: a fin of no volume, the
  // kink's node on nothing else. Both are dropped, the faces then meet along the chord, and the
  // kink's node is left out of its edges (expect_model_edge). Faces meshed alike (`alike`: pairs of
  // face tags) keep theirs. Call after the faces are added, before the model edges are declared.
  // Returns the triangles dropped.
  int64_t drop_fins(const std::set<std::pair<int, int>>& alike);

  // Declares a model edge: its nodes (3 doubles each, in order, as every face was given them) and how
  // many face uses it has in the B-rep. Call after the faces are added; conformity() then checks the
  // mesh against it.
  void expect_model_edge(const std::vector<double>& nodes, int face_uses);

  ConformityCounts conformity() const;
  // Per node of a face mesh: whether it is on the mesh's boundary (an edge only one triangle uses).
  static std::vector<char> boundary_nodes(size_t nodes, const std::vector<int32_t>& triangles);
  LambdaStats lambda() const;
  // The quads the file gets (see add_face): how many, their share of the 3D area, and their scaled
  // Jacobian (common/scaled_jacobian); all zero when there are none.
  struct QuadStats {
    int64_t quads = 0;
    double area_fraction = 0, scaled_jacobian_min = 0, scaled_jacobian_mean = 0;
    int64_t folded = 0;             // quads with a scaled Jacobian of 0 or less: folded or degenerate
    std::vector<int> folded_faces;  // the faces (tags) holding them, in order
  };
  QuadStats quads() const;
  static LambdaStats lambda_of(const std::vector<double>& xyz, const std::vector<int32_t>& triangles);

  // The mesh for a file (mesh_formats.hpp), a view of this object: one group "face_N" per face (MSH
  // physical group and entity, OBJ `g`, face_id), each node under the face that first contributed it.
  MeshDescription description() const;

  int64_t nodes() const { return static_cast<int64_t>(xyz_.size() / 3); }
  int64_t triangles() const { return static_cast<int64_t>(tris_.size() / 3); }

 private:
  int32_t weld(const double* p, int face_tag);
  // Two halves of one quad split again along its other diagonal where that makes the worse half
  // better (Lo lambda, at the welded nodes): a quad with a corner near 180 degrees has a half of no
  // area across its shorter diagonal, or gets one when welding moves a node by up to the tolerance,
  // and the check would call that a defect.
  // With `always`, the other diagonal whatever the quality: a half that folds onto a neighbouring
  // triangle (at a cone's apex, one half of each of the two quads there spans the cone through its
  // axis from the two sides of the seam) is no quad's only split.
  void resplit_quad(std::array<int32_t, 3>& t1, std::array<int32_t, 3>& t2, bool always = false) const;
  // Per triangle: whether another has the same three nodes (once each way: a zero-volume fold).
  static std::vector<char> folds_of(const std::vector<std::array<int32_t, 3>>& tris);
  // The quads (`quads`: per triangle, halves of one quad share a number >= 0, listed one after the
  // other) whose halves are in a fold, or whose diagonal other triangles use too once welded (a node
  // joined to both copies of a seam node), split the other way (resplit_quad): the diagonal is the
  // check's, the file has the quad. Returns whether any was.
  bool resplit_bad_diagonals(std::vector<std::array<int32_t, 3>>& tris, const std::vector<int64_t>& quads, const std::vector<char>& fold) const;
  int32_t find(const double* p) const;  // the welded node at p, or -1
  void note_defect(ConformityCounts& out, uint64_t key, int uses, int expected) const;

  std::vector<double> xyz_;
  std::vector<int> node_face_;          // face that first contributed the node (its MSH entity)
  std::vector<char> welded_;            // per node: on a face mesh's boundary, welded across faces
  std::set<int32_t> fin_nodes_;         // the kink nodes drop_fins left on no triangle
  std::vector<int32_t> tris_;
  std::vector<int> tri_face_;
  std::vector<int> tri_tag_;            // the face a triangle is written in
  std::vector<int64_t> tri_quad_;       // per triangle: the quad it is half of (numbered model-wide), or -1
  int64_t next_quad_ = 0;
  // The file's elements when there are quads: four nodes each, a triangle's fourth -1 (built by
  // description() from the triangles and their quads).
  void quad_elements(std::vector<int32_t>& elements, std::vector<int>& tags) const;
  mutable std::vector<int32_t> elements_;
  mutable std::vector<int> element_tags_;
  std::vector<int> face_tags_;          // in order of addition
  PointGrid grid_;                      // welded boundary nodes
  std::unordered_map<uint64_t, int> expected_uses_;  // node pair on a model edge -> face uses
};

}  // namespace wefm_cli
