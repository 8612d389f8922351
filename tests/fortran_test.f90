! The Fortran module against a brute-force search written here: 2-D and 3-D clouds, full and half
! lists, every metric, 0- and 1-based ids; the list's arrays are views of the C buffers; errors.
program fortran_test
  use, intrinsic :: iso_c_binding
  use, intrinsic :: ieee_arithmetic
  use horizon
  implicit none
  integer :: failures = 0, dims, metric, half_flag, based
  real(c_double), allocatable :: points(:, :)
  type(horizon_list) :: list
  integer :: ierr

  do dims = 2, 3
    call cloud(dims, 600, points)
    do metric = HORIZON_METRIC_L2, HORIZON_METRIC_LINF
      do half_flag = 0, 1
        do based = 0, 1
          call horizon_search(points, 1.1_c_double, list, ierr, half=half_flag == 1, metric=metric, &
                              one_based=based == 1)
          call check(ierr == HORIZON_OK, "search: " // horizon_error_message())
          call compare(points, 1.1_c_double, metric, half_flag == 1, based, list)
          ! A view, not a copy: the first id is the first element of horizon's C buffer.
          call check(c_associated(c_loc(list%indices(1)), horizon_list_indices_pointer(list%handle)), &
                     "indices is not a view of the C buffer")
          call horizon_free(list)
          call check(.not. associated(list%indices), "horizon_free left indices associated")
        end do
      end do
    end do
  end do

  ! Errors: a code and a message naming the cause.
  call horizon_search(points, -1.0_c_double, list, ierr)
  call check(ierr == HORIZON_INVALID_INPUT, "horizon -1 accepted")
  call check(index(horizon_error_message(), "horizon") > 0, "message: " // horizon_error_message())
  points(2, 5) = ieee_value(1.0_c_double, ieee_quiet_nan)
  call horizon_search(points, 1.0_c_double, list, ierr)
  call check(ierr == HORIZON_INVALID_INPUT, "NaN accepted")
  call check(index(horizon_error_message(), "point 4") > 0, "message: " // horizon_error_message())
  call horizon_search(points(:, 1:3), 1.0_c_double, list, ierr, backend=9)
  call check(ierr == HORIZON_INVALID_INPUT, "backend 9 accepted")
  call check(len(horizon_version_string()) >= 5, "version: " // horizon_version_string())

  deallocate(points)
  if (failures > 0) then
    print '(i0, a)', failures, " failures"
    error stop 1
  end if
  print '(a, a)', "fortran module: every list equal to the brute-force one; horizon ", horizon_version_string()

contains

  subroutine cloud(dims, n, points)  ! a fixed pseudo-random cloud in [0, 10)^dims
    integer, intent(in) :: dims, n
    real(c_double), allocatable, intent(out) :: points(:, :)
    integer(c_int64_t) :: state
    integer :: i, a
    allocate(points(dims, n))
    state = 12345
    do i = 1, n
      do a = 1, dims
        state = modulo(state * 1103515245_c_int64_t + 12345_c_int64_t, 2147483648_c_int64_t)
        points(a, i) = 10.0_c_double * real(state, c_double) / 2147483648.0_c_double
      end do
    end do
  end subroutine cloud

  logical function near(a, b, delta, metric)
    real(c_double), intent(in) :: a(:), b(:), delta
    integer, intent(in) :: metric
    select case (metric)
    case (HORIZON_METRIC_L1)
      near = sum(abs(a - b)) < delta
    case (HORIZON_METRIC_LINF)
      near = maxval(abs(a - b)) < delta
    case default
      if (size(a) == 3) then
        near = ((a(1) - b(1))**2 + (a(2) - b(2))**2) + (a(3) - b(3))**2 < delta**2
      else
        near = (a(1) - b(1))**2 + (a(2) - b(2))**2 < delta**2
      end if
    end select
  end function near

  subroutine compare(points, delta, metric, half, based, list)
    real(c_double), intent(in) :: points(:, :), delta
    integer, intent(in) :: metric, based
    logical, intent(in) :: half
    type(horizon_list), intent(in) :: list
    integer :: i, j, count
    integer(c_int64_t) :: start
    call check(list%n == size(points, 2), "row count")
    call check(list%total == list%offsets(list%n + 1) - based, "total")
    call check(size(list%indices) == list%total, "indices length")
    do i = 1, size(points, 2)
      start = list%offsets(i) + 1 - based  ! the 1-based position of row i's first id
      count = 0
      do j = 1, size(points, 2)
        if (j == i .or. (half .and. j < i)) cycle
        if (.not. near(points(:, i), points(:, j), delta, metric)) cycle
        if (start + count > list%offsets(i + 1) - based) then
          call check(.false., "row too short")
          return
        end if
        ! Rows are sorted by id, as the brute-force loop visits them.
        if (list%indices(start + count) /= j - 1 + based) then
          call check(.false., "wrong id")
          return
        end if
        count = count + 1
      end do
      call check(list%offsets(i + 1) - list%offsets(i) == count, "row length")
    end do
  end subroutine compare

  subroutine check(condition, what)
    logical, intent(in) :: condition
    character(len=*), intent(in) :: what
    if (.not. condition) then
      failures = failures + 1
      if (failures <= 10) print '(a, a)', "FAILED: ", what
    end if
  end subroutine check

end program fortran_test
