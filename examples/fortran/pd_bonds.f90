! A bond-based peridynamic force loop over horizon's list: a cube of points under a uniform
! stretch. Every bond of an interior point (farther than the horizon from the surface) has its
! mirror image, so the net force on it vanishes; points near the surface feel the missing bonds.
program pd_bonds
  use, intrinsic :: iso_c_binding
  use horizon
  implicit none
  integer, parameter :: n = 24                        ! points per side
  real(c_double), parameter :: h = 10.0_c_double / n  ! spacing
  real(c_double), parameter :: delta = 3.015_c_double * h, c = 1.0_c_double, strain = 1.0e-3_c_double
  real(c_double) :: x(3, n**3), y(3, n**3), force(3, n**3), xi(3), eta(3), stretch
  real(c_double) :: interior_max, surface_max
  type(horizon_list) :: list
  integer :: i, j, ierr, p
  integer(c_int64_t) :: b

  p = 0
  do i = 0, n**3 - 1
    p = p + 1
    x(:, p) = ([real(c_double) :: modulo(i, n), modulo(i / n, n), i / n**2] + 0.5_c_double) * h
  end do
  y = x * (1.0_c_double + strain)                      ! deformed positions

  call horizon_search(x, delta, list, ierr, one_based=.true.)
  if (ierr /= HORIZON_OK) then
    print *, "horizon: ", horizon_error_message()
    error stop 2
  end if

  force = 0
  do i = 1, n**3
    do b = list%offsets(i), list%offsets(i + 1) - 1  ! the family of point i (1-based ids)
      j = list%indices(b)
      xi = x(:, j) - x(:, i)
      eta = y(:, j) - y(:, i)
      stretch = (norm2(eta) - norm2(xi)) / norm2(xi)
      force(:, i) = force(:, i) + c * stretch * eta / norm2(eta)
    end do
  end do

  interior_max = 0
  surface_max = 0
  do i = 1, n**3
    if (all(x(:, i) > delta .and. x(:, i) < 10.0_c_double - delta)) then
      interior_max = max(interior_max, norm2(force(:, i)))
    else
      surface_max = max(surface_max, norm2(force(:, i)))
    end if
  end do
  print '(a, i0, a, i0, a)', "pd_bonds: ", n**3, " points, ", list%total, " bonds"
  print '(a, es10.3, a, es10.3)', "largest net force: interior ", interior_max, ", near the surface ", surface_max
  call horizon_free(list)
  if (interior_max > 1.0e-9_c_double * surface_max .or. surface_max == 0) error stop 1
end program pd_bonds
