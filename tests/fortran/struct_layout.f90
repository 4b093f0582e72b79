! Prints sizeof and field offsets of the bind(C) types in module wefm, in the format of
! tests/python/c/struct_layout.c, so tests/python/test_layout.py can compare them with C.
program struct_layout
  use wefm
  implicit none
  type(wefm_options), target :: o
  type(wefm_mesh_info), target :: i
  type(wefm_report), target :: r
  type(wefm_mesh_options), target :: m
  type(wefm_mesh_report), target :: q

  print '(a,i0)', 'wefm_options sizeof ', c_sizeof(o)
  call at('wefm_options struct_size', c_loc(o), c_loc(o%struct_size))
  call at('wefm_options s', c_loc(o), c_loc(o%s))
  call at('wefm_options k', c_loc(o), c_loc(o%k))
  call at('wefm_options boundary_weight', c_loc(o), c_loc(o%boundary_weight))
  call at('wefm_options curvature_adjust', c_loc(o), c_loc(o%curvature_adjust))
  call at('wefm_options method', c_loc(o), c_loc(o%method))
  call at('wefm_options solver', c_loc(o), c_loc(o%solver))
  call at('wefm_options default_edge_mode', c_loc(o), c_loc(o%default_edge_mode))
  call at('wefm_options s_step', c_loc(o), c_loc(o%s_step))
  call at('wefm_options rho_tolerance', c_loc(o), c_loc(o%rho_tolerance))
  call at('wefm_options max_rho_iterations', c_loc(o), c_loc(o%max_rho_iterations))
  call at('wefm_options rollout_tolerance', c_loc(o), c_loc(o%rollout_tolerance))
  call at('wefm_options max_rollout_sweeps', c_loc(o), c_loc(o%max_rollout_sweeps))
  call at('wefm_options score_threshold', c_loc(o), c_loc(o%score_threshold))
  call at('wefm_options auto_cut', c_loc(o), c_loc(o%auto_cut))
  call at('wefm_options threads', c_loc(o), c_loc(o%threads))
  call at('wefm_options memory_limit_mb', c_loc(o), c_loc(o%memory_limit_mb))
  call at('wefm_options min_beta', c_loc(o), c_loc(o%min_beta))
  call at('wefm_options residual', c_loc(o), c_loc(o%residual))

  print '(a,i0)', 'wefm_mesh_info sizeof ', c_sizeof(i)
  call at('wefm_mesh_info struct_size', c_loc(i), c_loc(i%struct_size))
  call at('wefm_mesh_info vertices', c_loc(i), c_loc(i%vertices))
  call at('wefm_mesh_info triangles', c_loc(i), c_loc(i%triangles))
  call at('wefm_mesh_info boundary_loops', c_loc(i), c_loc(i%boundary_loops))
  call at('wefm_mesh_info components', c_loc(i), c_loc(i%components))
  call at('wefm_mesh_info genus', c_loc(i), c_loc(i%genus))
  call at('wefm_mesh_info non_manifold_edges', c_loc(i), c_loc(i%non_manifold_edges))
  call at('wefm_mesh_info non_manifold_vertices', c_loc(i), c_loc(i%non_manifold_vertices))
  call at('wefm_mesh_info degenerate_triangles', c_loc(i), c_loc(i%degenerate_triangles))
  call at('wefm_mesh_info duplicate_triangles', c_loc(i), c_loc(i%duplicate_triangles))
  call at('wefm_mesh_info inconsistent_edges', c_loc(i), c_loc(i%inconsistent_edges))
  call at('wefm_mesh_info merged_vertices', c_loc(i), c_loc(i%merged_vertices))
  call at('wefm_mesh_info bbox_min', c_loc(i), c_loc(i%bbox_min))
  call at('wefm_mesh_info bbox_max', c_loc(i), c_loc(i%bbox_max))
  call at('wefm_mesh_info area', c_loc(i), c_loc(i%area))
  call at('wefm_mesh_info mean_edge_length', c_loc(i), c_loc(i%mean_edge_length))

  print '(a,i0)', 'wefm_report sizeof ', c_sizeof(r)
  call at('wefm_report struct_size', c_loc(r), c_loc(r%struct_size))
  call at('wefm_report score', c_loc(r), c_loc(r%score))
  call at('wefm_report flipped_triangles', c_loc(r), c_loc(r%flipped_triangles))
  call at('wefm_report boundary_intersections', c_loc(r), c_loc(r%boundary_intersections))
  call at('wefm_report area_distortion_mean', c_loc(r), c_loc(r%area_distortion_mean))
  call at('wefm_report area_distortion_max', c_loc(r), c_loc(r%area_distortion_max))
  call at('wefm_report angle_distortion_mean', c_loc(r), c_loc(r%angle_distortion_mean))
  call at('wefm_report angle_distortion_max', c_loc(r), c_loc(r%angle_distortion_max))
  call at('wefm_report uv_area', c_loc(r), c_loc(r%uv_area))
  call at('wefm_report area_3d', c_loc(r), c_loc(r%area_3d))
  call at('wefm_report s', c_loc(r), c_loc(r%s))
  call at('wefm_report converged', c_loc(r), c_loc(r%converged))
  call at('wefm_report method', c_loc(r), c_loc(r%method))
  call at('wefm_report s_steps', c_loc(r), c_loc(r%s_steps))
  call at('wefm_report rho_iterations', c_loc(r), c_loc(r%rho_iterations))
  call at('wefm_report rho_change', c_loc(r), c_loc(r%rho_change))
  call at('wefm_report symbolic_analyses', c_loc(r), c_loc(r%symbolic_analyses))
  call at('wefm_report numeric_factorizations', c_loc(r), c_loc(r%numeric_factorizations))
  call at('wefm_report solves', c_loc(r), c_loc(r%solves))
  call at('wefm_report iterative_iterations', c_loc(r), c_loc(r%iterative_iterations))
  call at('wefm_report auto_cut', c_loc(r), c_loc(r%auto_cut))
  call at('wefm_report degenerate_triangles', c_loc(r), c_loc(r%degenerate_triangles))
  call at('wefm_report time_topology', c_loc(r), c_loc(r%time_topology))
  call at('wefm_report time_coefficients', c_loc(r), c_loc(r%time_coefficients))
  call at('wefm_report time_assembly', c_loc(r), c_loc(r%time_assembly))
  call at('wefm_report time_analysis', c_loc(r), c_loc(r%time_analysis))
  call at('wefm_report time_factorization', c_loc(r), c_loc(r%time_factorization))
  call at('wefm_report time_solve', c_loc(r), c_loc(r%time_solve))
  call at('wefm_report time_continuation', c_loc(r), c_loc(r%time_continuation))
  call at('wefm_report time_quality', c_loc(r), c_loc(r%time_quality))
  call at('wefm_report time_total', c_loc(r), c_loc(r%time_total))
  call at('wefm_report peak_memory_mb', c_loc(r), c_loc(r%peak_memory_mb))
  call at('wefm_report min_beta_raised', c_loc(r), c_loc(r%min_beta_raised))
  call at('wefm_report boundary_unwind', c_loc(r), c_loc(r%boundary_unwind))

  print '(a,i0)', 'wefm_mesh_options sizeof ', c_sizeof(m)
  call at('wefm_mesh_options struct_size', c_loc(m), c_loc(m%struct_size))
  call at('wefm_mesh_options type', c_loc(m), c_loc(m%type))
  call at('wefm_mesh_options size', c_loc(m), c_loc(m%size))
  call at('wefm_mesh_options corners', c_loc(m), c_loc(m%corners))
  call at('wefm_mesh_options quads', c_loc(m), c_loc(m%quads))
  call at('wefm_mesh_options smoothing_iterations', c_loc(m), c_loc(m%smoothing_iterations))
  call at('wefm_mesh_options corner_angle_deg', c_loc(m), c_loc(m%corner_angle_deg))
  call at('wefm_mesh_options min_angle_deg', c_loc(m), c_loc(m%min_angle_deg))
  call at('wefm_mesh_options max_elements', c_loc(m), c_loc(m%max_elements))

  print '(a,i0)', 'wefm_mesh_report sizeof ', c_sizeof(q)
  call at('wefm_mesh_report struct_size', c_loc(q), c_loc(q%struct_size))
  call at('wefm_mesh_report nodes', c_loc(q), c_loc(q%nodes))
  call at('wefm_mesh_report elements', c_loc(q), c_loc(q%elements))
  call at('wefm_mesh_report nodes_per_element', c_loc(q), c_loc(q%nodes_per_element))
  call at('wefm_mesh_report lambda_mesh', c_loc(q), c_loc(q%lambda_mesh))
  call at('wefm_mesh_report lambda_min', c_loc(q), c_loc(q%lambda_min))
  call at('wefm_mesh_report fraction_below_0_6', c_loc(q), c_loc(q%fraction_below_0_6))
  call at('wefm_mesh_report scaled_jacobian_min', c_loc(q), c_loc(q%scaled_jacobian_min))
  call at('wefm_mesh_report scaled_jacobian_mean', c_loc(q), c_loc(q%scaled_jacobian_mean))
  call at('wefm_mesh_report wiggle_max', c_loc(q), c_loc(q%wiggle_max))
  call at('wefm_mesh_report wiggle_mean', c_loc(q), c_loc(q%wiggle_mean))
  call at('wefm_mesh_report time_boundary', c_loc(q), c_loc(q%time_boundary))
  call at('wefm_mesh_report time_mesh', c_loc(q), c_loc(q%time_mesh))
  call at('wefm_mesh_report time_smooth', c_loc(q), c_loc(q%time_smooth))
  call at('wefm_mesh_report time_map', c_loc(q), c_loc(q%time_map))

contains

  subroutine at(label, base, field)
    character(len=*), intent(in) :: label
    type(c_ptr), intent(in) :: base, field
    integer(c_intptr_t) :: b, f
    b = transfer(base, b)
    f = transfer(field, f)
    print '(a,1x,i0)', label, f - b
  end subroutine

end program struct_layout
