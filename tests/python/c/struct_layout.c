/* Prints sizeof and every field offset of the public structs, as the C compiler lays them out,
 * for tests/python/test_layout.py to compare with the ctypes mirrors and the Fortran types. */
#include <stddef.h>
#include <stdio.h>
#include <wefm/wefm.h>

#define SIZE(s) printf(#s " sizeof %zu\n", sizeof(s))
#define FIELD(s, f) printf(#s " " #f " %zu\n", offsetof(s, f))

int main(void) {
  SIZE(wefm_options);
  FIELD(wefm_options, struct_size); FIELD(wefm_options, s); FIELD(wefm_options, k);
  FIELD(wefm_options, boundary_weight); FIELD(wefm_options, curvature_adjust);
  FIELD(wefm_options, method); FIELD(wefm_options, solver); FIELD(wefm_options, default_edge_mode);
  FIELD(wefm_options, s_step); FIELD(wefm_options, rho_tolerance);
  FIELD(wefm_options, max_rho_iterations); FIELD(wefm_options, rollout_tolerance);
  FIELD(wefm_options, max_rollout_sweeps); FIELD(wefm_options, score_threshold);
  FIELD(wefm_options, auto_cut); FIELD(wefm_options, threads);
  FIELD(wefm_options, memory_limit_mb); FIELD(wefm_options, min_beta); FIELD(wefm_options, residual);

  SIZE(wefm_mesh_info);
  FIELD(wefm_mesh_info, struct_size); FIELD(wefm_mesh_info, vertices); FIELD(wefm_mesh_info, triangles);
  FIELD(wefm_mesh_info, boundary_loops); FIELD(wefm_mesh_info, components); FIELD(wefm_mesh_info, genus);
  FIELD(wefm_mesh_info, non_manifold_edges); FIELD(wefm_mesh_info, non_manifold_vertices);
  FIELD(wefm_mesh_info, degenerate_triangles); FIELD(wefm_mesh_info, duplicate_triangles);
  FIELD(wefm_mesh_info, inconsistent_edges); FIELD(wefm_mesh_info, merged_vertices);
  FIELD(wefm_mesh_info, bbox_min); FIELD(wefm_mesh_info, bbox_max); FIELD(wefm_mesh_info, area);
  FIELD(wefm_mesh_info, mean_edge_length);

  SIZE(wefm_report);
  FIELD(wefm_report, struct_size); FIELD(wefm_report, score); FIELD(wefm_report, flipped_triangles);
  FIELD(wefm_report, boundary_intersections); FIELD(wefm_report, area_distortion_mean);
  FIELD(wefm_report, area_distortion_max); FIELD(wefm_report, angle_distortion_mean);
  FIELD(wefm_report, angle_distortion_max); FIELD(wefm_report, uv_area); FIELD(wefm_report, area_3d);
  FIELD(wefm_report, s); FIELD(wefm_report, converged); FIELD(wefm_report, method);
  FIELD(wefm_report, s_steps); FIELD(wefm_report, rho_iterations); FIELD(wefm_report, rho_change);
  FIELD(wefm_report, symbolic_analyses); FIELD(wefm_report, numeric_factorizations);
  FIELD(wefm_report, solves); FIELD(wefm_report, iterative_iterations); FIELD(wefm_report, auto_cut);
  FIELD(wefm_report, degenerate_triangles); FIELD(wefm_report, time_topology);
  FIELD(wefm_report, time_coefficients); FIELD(wefm_report, time_assembly);
  FIELD(wefm_report, time_analysis); FIELD(wefm_report, time_factorization);
  FIELD(wefm_report, time_solve); FIELD(wefm_report, time_continuation);
  FIELD(wefm_report, time_quality); FIELD(wefm_report, time_total); FIELD(wefm_report, peak_memory_mb);
  FIELD(wefm_report, min_beta_raised); FIELD(wefm_report, boundary_unwind);
  FIELD(wefm_report, auto_cut_edges); FIELD(wefm_report, auto_cut_uncut_kept);
  FIELD(wefm_report, auto_cut_length); FIELD(wefm_report, auto_cut_other_score);
  FIELD(wefm_report, via_s); FIELD(wefm_report, boundary_unwind_weight);
  FIELD(wefm_report, abandoned_steps);

  SIZE(wefm_mesh_options);
  FIELD(wefm_mesh_options, struct_size); FIELD(wefm_mesh_options, type); FIELD(wefm_mesh_options, size);
  FIELD(wefm_mesh_options, corners); FIELD(wefm_mesh_options, quads);
  FIELD(wefm_mesh_options, smoothing_iterations); FIELD(wefm_mesh_options, corner_angle_deg);
  FIELD(wefm_mesh_options, min_angle_deg); FIELD(wefm_mesh_options, max_elements);

  SIZE(wefm_mesh_report);
  FIELD(wefm_mesh_report, struct_size); FIELD(wefm_mesh_report, nodes); FIELD(wefm_mesh_report, elements);
  FIELD(wefm_mesh_report, nodes_per_element); FIELD(wefm_mesh_report, lambda_mesh);
  FIELD(wefm_mesh_report, lambda_min); FIELD(wefm_mesh_report, fraction_below_0_6);
  FIELD(wefm_mesh_report, scaled_jacobian_min); FIELD(wefm_mesh_report, scaled_jacobian_mean);
  FIELD(wefm_mesh_report, wiggle_max); FIELD(wefm_mesh_report, wiggle_mean);
  FIELD(wefm_mesh_report, time_boundary); FIELD(wefm_mesh_report, time_mesh);
  FIELD(wefm_mesh_report, time_smooth); FIELD(wefm_mesh_report, time_map);
  return 0;
}
