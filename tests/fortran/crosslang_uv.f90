! Cross-language check, Fortran side: the same job as tests/python/c/crosslang_uv.c, through the
! 1-based wrappers of module wefm (the mesh file holds 0-based indices, converted here and back).
program crosslang_uv
  use wefm
  implicit none
  character(len=4096) :: mesh_path, uv_path
  integer :: nv, nt, unit, k
  real(c_double), allocatable :: xyz(:, :), uv(:, :)
  integer, allocatable :: tri(:, :)
  type(c_ptr) :: face

  face = c_null_ptr
  if (command_argument_count() /= 2) error stop "usage: crosslang_uv MESH.txt UV.txt"
  call get_command_argument(1, mesh_path)
  call get_command_argument(2, uv_path)
  open(newunit=unit, file=trim(mesh_path), status="old", action="read")
  read(unit, *) nv, nt
  allocate(xyz(3, nv), tri(3, nt))
  read(unit, *) xyz
  read(unit, *) tri
  close(unit)
  tri = tri + 1

  call check(wefm_face_create(face), "create")
  call check(wefm_f_set_mesh(face, xyz, tri), "set_mesh")
  call check(wefm_face_solve(face), "solve")
  call check(wefm_f_get_uv(face, uv), "get_uv")

  open(newunit=unit, file=trim(uv_path), status="replace", action="write")
  do k = 1, size(uv, 2)
    write(unit, '(es26.17e3,1x,es26.17e3)') uv(1, k), uv(2, k)
  end do
  close(unit)
  call wefm_face_release(face)

contains

  subroutine check(status, what)
    integer(c_int), intent(in) :: status
    character(len=*), intent(in) :: what
    if (status /= WEFM_OK) then
      write(0, '(a)') what // ": " // wefm_f_status_name(status) // ": " // wefm_f_message(face)
      error stop 1
    end if
  end subroutine

end program crosslang_uv
