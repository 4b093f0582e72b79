!> wefm: Fortran bindings (iso_c_binding) of the wefm C API, capi/include/wefm/wefm.h.
!>
!> Two layers in one module:
!>  * wefm_* : constants, bind(C) types (wefm_types.inc) and bind(C) interfaces for every C function
!>    (wefm_interfaces.inc), 0-based indices exactly as in C. Both are generated from wefm.h by
!>    scripts/gen_bindings.py (bindings/README.md). Array arguments are type(c_ptr) so that NULL
!>    (c_null_ptr) can be passed where the header allows it (size queries, optional outputs): pass
!>    c_loc(array) of a contiguous target array. WEFM_VERSION_NUMBER is WEFM_HEADER_VERSION_NUMBER
!>    here: Fortran names are case-insensitive and the function wefm_version_number() takes it.
!>  * wefm_f_* : thin wrappers (wefm_f_wrappers.inc, hand-written) taking Fortran arrays with 1-BASED
!>    vertex, use and triangle indices (converted once at the boundary), allocating outputs and
!>    returning strings.
!> Every function returns the wefm_status as integer(c_int); WEFM_OK is 0.
module wefm
  use, intrinsic :: iso_c_binding
  implicit none

  include 'wefm_types.inc'
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
