! Flatten a triangulated face from a mesh file and write OBJ with UVs, from Fortran.
!   flatten_obj IN.obj OUT.obj
! Shows the raw interfaces (wefm_face_*) next to the 1-based wrappers (wefm_f_*).
program flatten_obj
  use wefm
  implicit none
  character(len=4096) :: in_path, out_path
  type(c_ptr) :: mesh, face
  type(wefm_options) :: options
  type(wefm_report) :: report
  integer(c_int) :: status

  face = c_null_ptr
  if (command_argument_count() /= 2) then
    print '(a)', "usage: flatten_obj IN.obj OUT.obj"
    stop 2
  end if
  call get_command_argument(1, in_path)
  call get_command_argument(2, out_path)
  print '(a)', "wefm " // wefm_f_version()

  ! Reading has no handle yet: its message is the thread-local wefm_last_error().
  call check(wefm_f_mesh_read(trim(in_path), mesh), "read " // trim(in_path))
  call check(wefm_face_create(face), "create")
  call check(wefm_face_set_mesh_from(face, mesh), "set_mesh_from")
  call wefm_mesh_release(mesh)            ! the face copied what it needs

  call wefm_f_init(options)               ! library defaults, then change what we need
  options%s = 1.0_c_double
  call check(wefm_face_set_options(face, options), "set_options")

  status = wefm_face_solve(face)
  if (status == WEFM_ERROR_NOT_CONVERGED) then
    print '(a)', "warning: " // wefm_f_message(face) // " (keeping the best result)"
  else
    call check(status, "solve")
  end if
  call check(wefm_f_get_report(face, report), "report")
  call check(wefm_f_write_obj(face, trim(out_path)), "write " // trim(out_path))
  print '(a,f10.6,a,f10.6)', "score ", report%score, "  angle distortion max ", &
    report%angle_distortion_max
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

end program flatten_obj
