#pragma once
// A face as the C API sees it: mesh, topology spec, options, constraints and the last result, with
// the invalidation rules of wefm.h (new mesh clears everything, topology or constraint changes clear
// the result, a failed solve keeps the previous result).
#include <atomic>
#include <map>
#include <memory>
#include <optional>

#include "wefm/core/mesh/auto_cut.hpp"
#include "wefm/core/solve/flatten.hpp"

namespace wefm {

class Face {
 public:
  void set_mesh(TriMesh mesh);
  bool has_mesh() const { return has_mesh_; }
  const TriMesh& mesh() const { return mesh_; }

  void set_options(const Options& o);
  const Options& options() const { return options_; }

  void clear_topology();
  Index add_edge(std::vector<Index> chain);
  Index add_loop(std::vector<EdgeUse> loop);
  void set_outer_loop(Index loop);
  void add_seams(const std::vector<std::pair<Index, Index>>& seams);
  void set_edge_mode(Index edge, EdgeMode mode);
  const TopologySpec& spec() const { return spec_; }

  // Builds and validates on first use after a change; with options().auto_cut, an annulus or a
  // closed genus-0 surface without caller seams or loops is cut first (auto_cut()).
  const Topology& topology();
  const AutoCut& auto_cut() const { return cut_; }

  // Caller 3D nodes along an edge for meshing (wefm_face_set_edge_nodes), checked to lie on the
  // edge's facet chain; forgotten when the mesh or the topology changes.
  void set_edge_nodes(Index edge, std::vector<Vec3> nodes);
  void clear_edge_nodes() { edge_nodes_.clear(); }
  const std::map<Index, std::vector<Vec3>>& edge_nodes() const { return edge_nodes_; }

  Index add_constraint(LinearRow row);
  void clear_constraints();
  const std::vector<LinearRow>& constraints() const { return rows_; }

  // Throws on failure, leaving the previous result in place. Non-convergence stores the result and
  // then throws Error(not_converged).
  void solve(const ProgressFn& progress, const std::atomic<bool>* cancel);
  bool has_result() const { return result_.has_value(); }
  const FlattenResult& result() const;

 private:
  void require_mesh(const char* what) const;
  void topology_changed();
  bool auto_cut_applies() const;

  TriMesh mesh_;
  HalfEdges half_edges_;  // from validating the mesh; every topology of this mesh starts from them
  bool has_mesh_ = false;
  TopologySpec spec_;
  std::optional<Topology> topo_;
  AutoCut cut_;  // the automatic cut inside topo_, if any
  Options options_;
  std::vector<LinearRow> rows_;
  std::optional<FlattenResult> result_;
  std::map<Index, std::vector<Vec3>> edge_nodes_;
};

}  // namespace wefm
