!> wefm: Fortran bindings (iso_c_binding) of the wefm C API, capi/include/wefm/wefm.h.
!>
!> Two layers in one module:
!>  * wefm_* : bind(C) interfaces for every C function, 0-based indices exactly as in C. Array
!>    arguments are type(c_ptr) so that NULL (c_null_ptr) can be passed where the header allows it
!>    (size queries, optional outputs): pass c_loc(array) of a contiguous target array.
!>  * wefm_f_* : thin wrappers (wefm_f_wrappers.inc) taking Fortran arrays with 1-BASED vertex, use and
!>    triangle indices (converted once at the boundary), allocating outputs and returning strings.
!> Every function returns the wefm_status as integer(c_int); WEFM_OK is 0.
module wefm
  use, intrinsic :: iso_c_binding
  implicit none

  ! ---- wefm_status -------------------------------------------------------------------------
  integer(c_int), parameter :: WEFM_OK = 0
  integer(c_int), parameter :: WEFM_ERROR_NULL_ARGUMENT = 1
  integer(c_int), parameter :: WEFM_ERROR_INVALID_ARGUMENT = 2
  integer(c_int), parameter :: WEFM_ERROR_OUT_OF_RANGE = 3
  integer(c_int), parameter :: WEFM_ERROR_BUFFER_TOO_SMALL = 4
  integer(c_int), parameter :: WEFM_ERROR_INVALID_STATE = 5
  integer(c_int), parameter :: WEFM_ERROR_INVALID_MESH = 6
  integer(c_int), parameter :: WEFM_ERROR_INVALID_TOPOLOGY = 7
  integer(c_int), parameter :: WEFM_ERROR_INVALID_CONSTRAINT = 8
  integer(c_int), parameter :: WEFM_ERROR_SINGULAR = 9
  integer(c_int), parameter :: WEFM_ERROR_NOT_POSITIVE_DEFINITE = 10
  integer(c_int), parameter :: WEFM_ERROR_NOT_CONVERGED = 11
  integer(c_int), parameter :: WEFM_ERROR_CANCELLED = 12
  integer(c_int), parameter :: WEFM_ERROR_OUT_OF_MEMORY = 13
  integer(c_int), parameter :: WEFM_ERROR_IO = 14
  integer(c_int), parameter :: WEFM_ERROR_UNSUPPORTED = 15
  integer(c_int), parameter :: WEFM_ERROR_OUTSIDE_DOMAIN = 16
  integer(c_int), parameter :: WEFM_ERROR_INTERNAL = 99

  ! ---- version of the header these bindings mirror ------------------------------------------
  integer(c_int), parameter :: WEFM_VERSION_MAJOR = 0, WEFM_VERSION_MINOR = 1, WEFM_VERSION_PATCH = 0
  ! WEFM_VERSION_NUMBER is renamed: Fortran names are case-insensitive and the function
  ! wefm_version_number() takes that name.
  integer(c_int), parameter :: WEFM_HEADER_VERSION_NUMBER = &
    WEFM_VERSION_MAJOR * 10000 + WEFM_VERSION_MINOR * 100 + WEFM_VERSION_PATCH

  ! ---- wefm_method, wefm_edge_mode, wefm_solver, wefm_mesh_type ------------------------------
  integer(c_int), parameter :: WEFM_METHOD_GLOBAL = 0, WEFM_METHOD_ROLLOUT = 1
  integer(c_int), parameter :: WEFM_RESIDUAL_PER_HALF_EDGE = 0, WEFM_RESIDUAL_PER_USE = 1
  integer(c_int), parameter :: WEFM_EDGE_AUTO = 0, WEFM_EDGE_FREE = 1, WEFM_EDGE_PERIODIC = 2, &
                               WEFM_EDGE_SCAR = 3, WEFM_EDGE_ROTATIONAL = 4
  integer(c_int), parameter :: WEFM_SOLVER_AUTO = 0, WEFM_SOLVER_CHOLMOD = 1, WEFM_SOLVER_EIGEN = 2
  integer(c_int), parameter :: WEFM_MESH_FREE = 0, WEFM_MESH_TRANSFINITE = 1

  ! ---- structs (field order and kinds must match the header exactly) -------------------------
  type, bind(C) :: wefm_options
    integer(c_size_t) :: struct_size
    real(c_double) :: s, k, boundary_weight
    integer(c_int) :: curvature_adjust, method, solver, default_edge_mode
    real(c_double) :: s_step, rho_tolerance
    integer(c_int) :: max_rho_iterations
    real(c_double) :: rollout_tolerance
    integer(c_int) :: max_rollout_sweeps
    real(c_double) :: score_threshold
    integer(c_int) :: auto_cut, threads
    real(c_double) :: memory_limit_mb, min_beta
    integer(c_int) :: residual
  end type wefm_options

  type, bind(C) :: wefm_mesh_info
    integer(c_size_t) :: struct_size
    integer(c_int64_t) :: vertices, triangles, boundary_loops, components, genus
    integer(c_int64_t) :: non_manifold_edges, non_manifold_vertices, degenerate_triangles
    integer(c_int64_t) :: duplicate_triangles, inconsistent_edges, merged_vertices
    real(c_double) :: bbox_min(3), bbox_max(3)
    real(c_double) :: area, mean_edge_length
  end type wefm_mesh_info

  type, bind(C) :: wefm_report
    integer(c_size_t) :: struct_size
    real(c_double) :: score
    integer(c_int64_t) :: flipped_triangles, boundary_intersections
    real(c_double) :: area_distortion_mean, area_distortion_max
    real(c_double) :: angle_distortion_mean, angle_distortion_max
    real(c_double) :: uv_area, area_3d, s
    integer(c_int32_t) :: converged, method, s_steps, rho_iterations
    real(c_double) :: rho_change
    integer(c_int64_t) :: symbolic_analyses, numeric_factorizations, solves, iterative_iterations
    integer(c_int32_t) :: auto_cut, degenerate_triangles
    real(c_double) :: time_topology, time_coefficients, time_assembly, time_analysis, &
                      time_factorization, time_solve, time_continuation, time_quality, time_total
    real(c_double) :: peak_memory_mb
    integer(c_int32_t) :: min_beta_raised
    real(c_double) :: boundary_unwind
    integer(c_int32_t) :: auto_cut_edges, auto_cut_uncut_kept
    real(c_double) :: auto_cut_length, auto_cut_other_score
    real(c_double) :: via_s, boundary_unwind_weight
    integer(c_int32_t) :: abandoned_steps
  end type wefm_report

  type, bind(C) :: wefm_mesh_options
    integer(c_size_t) :: struct_size
    integer(c_int) :: type
    real(c_double) :: size
    integer(c_int32_t) :: corners(4)
    integer(c_int) :: quads, smoothing_iterations
    real(c_double) :: corner_angle_deg, min_angle_deg
    integer(c_int64_t) :: max_elements
  end type wefm_mesh_options

  type, bind(C) :: wefm_mesh_report
    integer(c_size_t) :: struct_size
    integer(c_int64_t) :: nodes, elements
    integer(c_int32_t) :: nodes_per_element
    real(c_double) :: lambda_mesh, lambda_min, fraction_below_0_6
    real(c_double) :: scaled_jacobian_min, scaled_jacobian_mean, wiggle_max, wiggle_mean
    real(c_double) :: time_boundary, time_mesh, time_smooth, time_map
  end type wefm_mesh_report

  include 'wefm_interfaces.inc'

  !> Safe defaults for any wefm struct: see wefm_f_init_* in wefm_f_wrappers.inc.
  interface wefm_f_init
    module procedure wefm_f_init_options, wefm_f_init_report, wefm_f_init_mesh_info, &
                     wefm_f_init_mesh_options, wefm_f_init_mesh_report
  end interface wefm_f_init

  private :: get_doubles, get_ints

contains

  include 'wefm_f_wrappers.inc'

end module wefm
