! A Fortran program built against an *installed* wefm with find_package(wefm) and the module `wefm`
! (tests/capi/consumer.cmake, MODE fortran): flatten two triangles through the 1-based wrappers.
program consumer
  use wefm
  implicit none
  real(c_double) :: xyz(3, 4)
  integer :: tri(3, 2)
  type(c_ptr) :: face
  type(wefm_options) :: options
  real(c_double), allocatable :: uv(:, :)

  xyz = reshape([0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 1d0, 1d0, 0d0, 0d0, 1d0, 0d0], [3, 4])
  tri = reshape([1, 2, 3, 1, 3, 4], [3, 2])
  face = c_null_ptr
  call wefm_f_init(options)
  if (wefm_face_create(face) /= WEFM_OK) error stop "create"
  if (wefm_f_set_mesh(face, xyz, tri) /= WEFM_OK) error stop "set_mesh"
  if (wefm_face_set_options(face, options) /= WEFM_OK) error stop "set_options"
  if (wefm_face_solve(face) /= WEFM_OK) error stop "solve"
  if (wefm_f_get_uv(face, uv) /= WEFM_OK) error stop "get_uv"
  if (size(uv, 2) /= 4) error stop "uv count"
  call wefm_face_release(face)
  print '(a,a,a,i0,a)', "consumer (Fortran): wefm ", wefm_f_version(), ", ", size(uv), " UV values"
  deallocate(uv)  ! main-program variables are never freed implicitly: LeakSanitizer would report it
end program
