!> horizon's Fortran 2008 module: neighbour lists through the C API (horizon/horizon.h) with
!> ISO_C_BINDING. The list's offsets and indices are Fortran pointers into horizon's own buffers
!> (no copy); with one_based = .true. ids and offsets count from 1, so the family of point i is
!> list%indices(list%offsets(i) : list%offsets(i + 1) - 1).
!>
!>   use horizon
!>   type(horizon_list) :: list
!>   call horizon_search(points, delta, list, ierr, one_based=.true.)   ! points(3, n) or (2, n)
!>   if (ierr /= HORIZON_OK) print *, horizon_error_message()
!>   call horizon_free(list)
module horizon
  use, intrinsic :: iso_c_binding
  implicit none
  private

  public :: horizon_list, horizon_search, horizon_free, horizon_error_message, horizon_version_string
  public :: horizon_list_indices_pointer

  integer, parameter, public :: HORIZON_OK = 0, HORIZON_INVALID_INPUT = 1, HORIZON_OUT_OF_MEMORY = 2, &
                                HORIZON_LIST_TOO_LARGE = 3, HORIZON_BACKEND_UNAVAILABLE = 4, &
                                HORIZON_DEVICE_OUT_OF_MEMORY = 5, HORIZON_INTERNAL_ERROR = 6
  integer, parameter, public :: HORIZON_METRIC_L2 = 0, HORIZON_METRIC_L1 = 1, HORIZON_METRIC_LINF = 2
  integer, parameter, public :: HORIZON_BACKEND_AUTO = 0, HORIZON_BACKEND_SERIAL = 1, &
                                HORIZON_BACKEND_OPENMP = 2, HORIZON_BACKEND_CUDA = 3

  !> The C struct horizon_options, field for field (uint64_t fields as int64: the same bytes).
  type, bind(c) :: options_c
    integer(c_size_t) :: size
    real(c_double) :: horizon
    integer(c_int32_t) :: metric, cells_per_horizon, half, sort_rows, backend, threads, device, reserved
    real(c_double) :: box(3)
    integer(c_int64_t) :: max_memory, gpu_max_memory
  end type options_c

  !> A neighbour list: n rows; offsets(n + 1) and indices(total) point into horizon's buffers.
  type :: horizon_list
    integer(c_int64_t), pointer :: offsets(:) => null()
    integer(c_int32_t), pointer :: indices(:) => null()
    integer(c_int64_t) :: n = 0, total = 0
    logical :: half = .false., one_based = .false.
    type(c_ptr) :: handle = c_null_ptr  !< the C list (horizon_list*), for the C API
  end type horizon_list

  integer(c_int32_t), target, save :: no_ids(0)

  interface
    subroutine c_options_default(options) bind(c, name="horizon_options_default")
      import :: options_c
      type(options_c), intent(out) :: options
    end subroutine
    integer(c_int) function c_search(points, n, dims, options, list) bind(c, name="horizon_search")
      import :: c_double, c_size_t, c_int, options_c, c_ptr
      real(c_double), intent(in) :: points(*)
      integer(c_size_t), value :: n
      integer(c_int), value :: dims
      type(options_c), intent(in) :: options
      type(c_ptr), intent(out) :: list
    end function
    integer(c_size_t) function c_list_size(list) bind(c, name="horizon_list_size")
      import :: c_size_t, c_ptr
      type(c_ptr), value :: list
    end function
    integer(c_int64_t) function c_list_total(list) bind(c, name="horizon_list_total")
      import :: c_int64_t, c_ptr
      type(c_ptr), value :: list
    end function
    type(c_ptr) function c_list_offsets(list) bind(c, name="horizon_list_offsets")
      import :: c_ptr
      type(c_ptr), value :: list
    end function
    !> The C buffer of the list's ids (what list%indices points into).
    type(c_ptr) function horizon_list_indices_pointer(list) bind(c, name="horizon_list_indices")
      import :: c_ptr
      type(c_ptr), value :: list
    end function
    integer(c_int) function c_list_make_one_based(list) bind(c, name="horizon_list_make_one_based")
      import :: c_int, c_ptr
      type(c_ptr), value :: list
    end function
    subroutine c_list_free(list) bind(c, name="horizon_list_free")
      import :: c_ptr
      type(c_ptr), value :: list
    end subroutine
    type(c_ptr) function c_last_error() bind(c, name="horizon_last_error")
      import :: c_ptr
    end function
    type(c_ptr) function c_version() bind(c, name="horizon_version")
      import :: c_ptr
    end function
    integer(c_size_t) function c_strlen(text) bind(c, name="strlen")
      import :: c_size_t, c_ptr
      type(c_ptr), value :: text
    end function
  end interface

contains

  !> The neighbour list of the points (points(:, i) is point i; 2 or 3 rows) within delta.
  !> ierr is HORIZON_OK or an error code (horizon_error_message() says why). Optional: half (each
  !> pair once), metric (HORIZON_METRIC_*), backend (HORIZON_BACKEND_*), threads, one_based.
  subroutine horizon_search(points, delta, list, ierr, half, metric, backend, threads, one_based)
    real(c_double), intent(in), contiguous :: points(:, :)
    real(c_double), intent(in) :: delta
    type(horizon_list), intent(inout) :: list
    integer, intent(out) :: ierr
    logical, intent(in), optional :: half, one_based
    integer, intent(in), optional :: metric, backend, threads
    type(options_c) :: options
    type(c_ptr) :: handle

    call horizon_free(list)
    call c_options_default(options)
    options%horizon = delta
    if (present(half)) options%half = merge(1, 0, half)
    if (present(metric)) options%metric = metric
    if (present(backend)) options%backend = backend
    if (present(threads)) options%threads = threads
    ierr = c_search(points, int(size(points, 2), c_size_t), int(size(points, 1), c_int), options, handle)
    if (ierr /= HORIZON_OK) return
    if (present(one_based)) then
      if (one_based) then
        ierr = c_list_make_one_based(handle)
        if (ierr /= HORIZON_OK) then
          call c_list_free(handle)
          return
        end if
        list%one_based = .true.
      end if
    end if
    list%handle = handle
    list%n = c_list_size(handle)
    list%total = c_list_total(handle)
    list%half = options%half /= 0
    call c_f_pointer(c_list_offsets(handle), list%offsets, [list%n + 1])
    if (list%total > 0) then
      call c_f_pointer(horizon_list_indices_pointer(handle), list%indices, [list%total])
    else
      list%indices => no_ids
    end if
  end subroutine horizon_search

  !> Frees the list's buffers (its pointers are nullified); a list never searched is left as is.
  subroutine horizon_free(list)
    type(horizon_list), intent(inout) :: list
    if (c_associated(list%handle)) call c_list_free(list%handle)
    list%handle = c_null_ptr
    nullify(list%offsets, list%indices)
    list%n = 0
    list%total = 0
    list%half = .false.
    list%one_based = .false.
  end subroutine horizon_free

  !> Why the last failed call on this thread failed.
  function horizon_error_message() result(message)
    character(len=:), allocatable :: message
    message = c_text(c_last_error())
  end function horizon_error_message

  !> The linked library's version, "MAJOR.MINOR.PATCH".
  function horizon_version_string() result(version)
    character(len=:), allocatable :: version
    version = c_text(c_version())
  end function horizon_version_string

  function c_text(text) result(string)
    type(c_ptr), intent(in) :: text
    character(len=:), allocatable :: string
    character(kind=c_char), pointer :: chars(:)
    integer :: i, length
    length = int(c_strlen(text))
    allocate(character(len=length) :: string)
    if (length == 0) return
    call c_f_pointer(text, chars, [length])
    do i = 1, length
      string(i:i) = chars(i)
    end do
  end function c_text

end module horizon
