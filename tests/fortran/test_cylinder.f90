! Fortran binding test: a cylinder band cut open along a generator (a disk) flattens without
! distortion, and failing calls return their status with a message.
program test_cylinder
  use wefm
  implicit none
  integer, parameter :: rings = 4, sectors = 16
  real(c_double), parameter :: pi = acos(-1.0_c_double)
  real(c_double), allocatable :: xyz(:, :), uv(:, :)
  integer, allocatable :: tri(:, :)
  integer(c_int32_t), allocatable :: tri_uses(:, :), use_vertex(:)
  type(wefm_report) :: report
  type(wefm_options) :: options
  type(c_ptr) :: face
  integer(c_int) :: status
  integer :: failures

  failures = 0
  call build_cut_cylinder(xyz, tri)

  call expect(wefm_face_create(face) == WEFM_OK, "create")
  ! Before any solve the results are an ordering error, with a message on the handle.
  status = wefm_f_set_mesh(face, xyz, tri)
  call expect(status == WEFM_OK, "set_mesh: " // wefm_f_message(face))
  status = wefm_f_get_uv(face, uv)
  call expect(status == WEFM_ERROR_INVALID_STATE, "uv before solve: " // wefm_f_status_name(status))
  call expect(len(wefm_f_message(face)) > 0, "uv before solve has a message")

  call expect(wefm_f_get_options(face, options) == WEFM_OK, "get_options")
  call expect(options%struct_size == c_sizeof(options), "struct_size is ours")
  call expect(options%s == 1.0_c_double, "default s = 1")

  status = wefm_face_solve(face)
  call expect(status == WEFM_OK, "solve: " // wefm_f_message(face))
  call expect(wefm_f_get_report(face, report) == WEFM_OK, "report")
  print '(a,es24.16)', "angle_distortion_max = ", report%angle_distortion_max
  call expect(report%angle_distortion_max < 1 + 1e-8_c_double, "zero angle distortion")
  call expect(report%flipped_triangles == 0, "no flips")

  call expect(wefm_f_get_uv(face, uv) == WEFM_OK, "uv")
  call expect(wefm_f_get_triangle_uses(face, tri_uses) == WEFM_OK, "triangle uses")
  call expect(wefm_f_get_use_vertices(face, use_vertex) == WEFM_OK, "use vertices")
  call expect(size(uv, 1) == 2 .and. size(uv, 2) == size(use_vertex), "uv shape")
  call expect(all(shape(tri_uses) == shape(tri)), "triangle uses shape")
  call expect(minval(tri_uses) == 1 .and. maxval(tri_uses) == size(use_vertex), "1-based uses")
  call expect(all(use_vertex(tri_uses(:, 1)) == tri(:, 1)), "uses map back to the 1-based vertices")
  call expect(edge_ratio_spread() < 1e-9_c_double, "isometric up to scale")

  ! A NaN coordinate is rejected with a message naming the vertex, and the face keeps its mesh.
  xyz(2, 5) = ieee_nan()
  status = wefm_f_set_mesh(face, xyz, tri)
  call expect(status == WEFM_ERROR_INVALID_MESH, "NaN: " // wefm_f_status_name(status))
  call expect(wefm_f_status_name(status) == "WEFM_ERROR_INVALID_MESH", "status name")
  print '(a)', "NaN message: " // wefm_f_message(face)
  call expect(index(wefm_f_message(face), "vertex 4") > 0, "message names vertex 4 (0-based)")

  call wefm_face_release(face)
  call expect(wefm_face_solve(c_null_ptr) == WEFM_ERROR_NULL_ARGUMENT, "NULL face")
  ! A main program's allocatables live to the end of the process; free them so LeakSanitizer
  ! (scripts/test.sh, stage sanitize) sees only real leaks.
  deallocate(xyz, tri, uv, tri_uses, use_vertex)

  if (failures > 0) then
    print '(i0,a)', failures, " check(s) failed"
    error stop 1
  end if
  print '(a)', "all Fortran checks passed"

contains

  subroutine build_cut_cylinder(xyz, tri)
    ! Rows on circles; column `sectors` repeats the positions of column 0 with new vertices.
    real(c_double), allocatable, intent(out) :: xyz(:, :)
    integer, allocatable, intent(out) :: tri(:, :)
    integer :: i, j, a, b, c, d, t
    allocate(xyz(3, (rings + 1) * (sectors + 1)), tri(3, 2 * rings * sectors))
    do i = 0, rings
      do j = 0, sectors
        xyz(:, vid(i, j)) = [cos(2 * pi * j / sectors), sin(2 * pi * j / sectors), 0.5_c_double * i]
      end do
    end do
    t = 0
    do i = 0, rings - 1
      do j = 0, sectors - 1
        a = vid(i, j); b = vid(i, j + 1); c = vid(i + 1, j + 1); d = vid(i + 1, j)
        tri(:, t + 1) = [a, b, c]
        tri(:, t + 2) = [a, c, d]
        t = t + 2
      end do
    end do
  end subroutine

  integer function vid(i, j)
    integer, intent(in) :: i, j
    vid = i * (sectors + 1) + j + 1
  end function

  real(c_double) function edge_ratio_spread()
    ! max/min over all triangle edges of |UV edge| / |3D edge|, minus one.
    real(c_double) :: r, lo, hi
    integer :: t, k, k2
    lo = huge(lo); hi = 0
    do t = 1, size(tri, 2)
      do k = 1, 3
        k2 = mod(k, 3) + 1
        r = norm2(uv(:, tri_uses(k2, t)) - uv(:, tri_uses(k, t))) / &
            norm2(xyz(:, tri(k2, t)) - xyz(:, tri(k, t)))
        lo = min(lo, r); hi = max(hi, r)
      end do
    end do
    edge_ratio_spread = hi / lo - 1
  end function

  real(c_double) function ieee_nan()
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    ieee_nan = ieee_value(1.0_c_double, ieee_quiet_nan)
  end function

  subroutine expect(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what
    if (.not. ok) then
      print '(a)', "FAILED: " // what
      failures = failures + 1
    end if
  end subroutine

end program test_cylinder
