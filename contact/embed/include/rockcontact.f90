! rockcontact.f90: Fortran 2003 bindings (iso_c_binding) to the C API in rockcontact.h; read
! that header for the units, preconditions and error handling. Compile this file with your
! program (module files are compiler-specific, so the source is what is installed) and link
! the rockcontact libraries with a C++-aware link line (see the README).
!
!   use rockcontact
!   type(rockcontact_params) :: params
!   type(c_ptr) :: contact
!   type(rockcontact_pair_result) :: r
!   call rockcontact_default_params(params)
!   if (rockcontact_evaluator_create(params, contact) /= ROCKCONTACT_OK) &
!     print *, rockcontact_last_error()
!   status = rockcontact_evaluate_pair(contact, a_xy, n_a, a_pose, b_xy, n_b, b_pose, r)
!   call rockcontact_evaluator_destroy(contact)
!
! Friction: keep one type(rockcontact_friction_state) per contacting pair (its default value,
! rockcontact_friction_state(), is a new contact) and after each evaluate_pair of that pair call
!   status = rockcontact_evaluate_friction(friction_params, r, increment, state, t)
! with increment(2) the relative displacement of the contact point since the previous call (m);
! t%force is the tangential force on a. A pair that separates resets its state.
!
! a_xy(2 * n_a) holds x1, y1, x2, y2, ... (local frame, m, counter-clockwise); a_pose(3) holds
! x, y (m) and theta (rad). Status codes and the result's `status` are the C enumerators.
module rockcontact
  use, intrinsic :: iso_c_binding, only: c_int, c_int32_t, c_int64_t, c_double, c_ptr, c_char, &
                                         c_null_char, c_f_pointer, c_associated
  implicit none
  private

  integer(c_int), parameter, public :: ROCKCONTACT_OK = 0, ROCKCONTACT_ERROR_INVALID_ARGUMENT = 1, &
                                       ROCKCONTACT_ERROR_INVALID_POLYGON = 2, &
                                       ROCKCONTACT_ERROR_OUT_OF_MEMORY = 3, &
                                       ROCKCONTACT_ERROR_INTERNAL = 4, &
                                       ROCKCONTACT_ERROR_INVALID_POLYHEDRON = 5
  integer(c_int32_t), parameter, public :: ROCKCONTACT_POLICY_FLOAT = 0, &
                                           ROCKCONTACT_POLICY_FILTERED = 1, &
                                           ROCKCONTACT_POLICY_EXACT = 2, &
                                           ROCKCONTACT_POLICY_CHECKED = 3
  integer(c_int32_t), parameter, public :: ROCKCONTACT_DEMARCATION_EXACT = 0, &
                                           ROCKCONTACT_DEMARCATION_PAPER = 1
  integer(c_int32_t), parameter, public :: ROCKCONTACT_SEPARATE = 0, ROCKCONTACT_TOUCH = 1, &
                                           ROCKCONTACT_OVERLAP = 2
  integer(c_int32_t), parameter, public :: ROCKCONTACT_FRICTION_ELASTOPLASTIC = 0, &
                                           ROCKCONTACT_FRICTION_PAPER = 1
  integer(c_int32_t), parameter, public :: ROCKCONTACT_VERTEX_FACE = 0, ROCKCONTACT_EDGE_EDGE = 1, &
                                           ROCKCONTACT_VERTEX_EDGE = 2, ROCKCONTACT_VERTEX_VERTEX = 3

  type, bind(C), public :: rockcontact_params
    real(c_double) :: kn                   ! Pa, > 0
    real(c_double) :: H                    ! m, > 0
    real(c_double) :: small_edge_fraction  ! paper demarcation only
    integer(c_int32_t) :: policy           ! ROCKCONTACT_POLICY_*
    integer(c_int32_t) :: demarcation      ! ROCKCONTACT_DEMARCATION_*
  end type

  type, bind(C), public :: rockcontact_pair_result
    integer(c_int32_t) :: status       ! ROCKCONTACT_SEPARATE, _TOUCH or _OVERLAP
    integer(c_int32_t) :: has_point    ! 1 when overlapping with a non-zero force
    real(c_double) :: force(2)         ! normal force on a, N/m; on b it is -force
    real(c_double) :: point(2)         ! contact point, m (when has_point = 1)
    real(c_double) :: area             ! intersection polygon area, m^2
    real(c_double) :: penetration      ! minimum translation distance, m
    integer(c_int64_t) :: predicates   ! predicate calls spent on the pair
    integer(c_int64_t) :: fallbacks    ! of which re-evaluated exactly
    real(c_double) :: length           ! contact length L (half the IP perimeter), m
  end type

  type, bind(C), public :: rockcontact_friction_params
    real(c_double) :: kt                  ! N/m per metre of thickness, > 0
    real(c_double) :: friction_angle_deg  ! phi, degrees, in [0, 90)
    real(c_double) :: cohesion            ! c, Pa, >= 0
    integer(c_int32_t) :: model           ! ROCKCONTACT_FRICTION_*
    integer(c_int32_t) :: reserved        ! explicit padding; ignored
  end type

  ! Opaque but copyable: store one per contacting pair, never edit its components.
  type, bind(C), public :: rockcontact_friction_state
    real(c_double) :: displacement(2) = 0.0_c_double
    real(c_double) :: force(2) = 0.0_c_double
    real(c_double) :: normal(2) = 0.0_c_double
    integer(c_int32_t) :: sliding = 0
    integer(c_int32_t) :: in_contact = 0
  end type

  type, bind(C), public :: rockcontact_friction_result
    real(c_double) :: force(2)     ! tangential force on a, N/m, at the contact point
    real(c_double) :: dissipated   ! energy the slip dissipated since the previous call, J/m
    integer(c_int32_t) :: sliding  ! 1 when |force| is at the Coulomb limit
    integer(c_int32_t) :: reserved ! explicit padding
  end type

  ! 3D (rockcontact.h): polyhedra in world coordinates, xyz(3 * n) = x1, y1, z1, x2, ...;
  ! face_sizes(f) vertices per face, faces = the faces' 0-based vertex indices one face after
  ! the other, each counter-clockwise seen from outside.
  type, bind(C), public :: rockcontact_params3d
    real(c_double) :: kn                ! N/m per constraint, > 0
    real(c_double) :: tolerance         ! m, >= 0
    integer(c_int32_t) :: policy        ! ROCKCONTACT_POLICY_*
    integer(c_int32_t) :: reserved      ! explicit padding; ignored
  end type

  type, bind(C), public :: rockcontact_pair3d_result
    integer(c_int32_t) :: status                 ! ROCKCONTACT_SEPARATE, _TOUCH or _OVERLAP
    integer(c_int32_t) :: constraint_count
    real(c_double) :: volume                     ! of the intersection, m^3
    real(c_double) :: distance                   ! m when separate, else -1
    real(c_double) :: depth                      ! penetration depth, m (overlap)
    real(c_double) :: normal(3)                  ! unit, from a towards b (overlap)
    integer(c_int32_t) :: contact_set_dimension  ! 0, 1, 2 when touching, else -1
    integer(c_int32_t) :: contact_set_count
    integer(c_int64_t) :: predicates
    integer(c_int64_t) :: fallbacks
  end type

  type, bind(C), public :: rockcontact_constraint3d
    integer(c_int32_t) :: type        ! ROCKCONTACT_VERTEX_FACE, ...
    integer(c_int32_t) :: reserved
    real(c_double) :: point_a(3)      ! m
    real(c_double) :: point_b(3)      ! m
    real(c_double) :: normal(3)       ! unit, from a towards b
    real(c_double) :: gap             ! m, negative = penetration
    real(c_double) :: force(3)        ! penalty force on b, N
  end type

  public :: rockcontact_default_params3d, rockcontact_evaluator3d_create, &
            rockcontact_evaluator3d_destroy, rockcontact_evaluate_pair3d, &
            rockcontact_pair3d_constraints, rockcontact_pair3d_contact_set

  public :: rockcontact_default_params, rockcontact_evaluator_create, &
            rockcontact_evaluator_destroy, rockcontact_evaluate_pair, &
            rockcontact_intersection_polygon, rockcontact_last_error, &
            rockcontact_version, rockcontact_default_friction_params, &
            rockcontact_evaluate_friction

  interface
    subroutine rockcontact_default_params(params) bind(C, name="rockcontact_default_params")
      import :: rockcontact_params
      type(rockcontact_params), intent(out) :: params
    end subroutine

    function rockcontact_evaluator_create(params, evaluator) result(code) &
        bind(C, name="rockcontact_evaluator_create")
      import :: rockcontact_params, c_ptr, c_int
      type(rockcontact_params), intent(in) :: params
      type(c_ptr), intent(out) :: evaluator
      integer(c_int) :: code
    end function

    subroutine rockcontact_evaluator_destroy(evaluator) bind(C, name="rockcontact_evaluator_destroy")
      import :: c_ptr
      type(c_ptr), value :: evaluator
    end subroutine

    function rockcontact_evaluate_pair(evaluator, a_xy, a_count, a_pose, b_xy, b_count, b_pose, &
                                       result) result(code) bind(C, name="rockcontact_evaluate_pair")
      import :: rockcontact_pair_result, c_ptr, c_int, c_int32_t, c_double
      type(c_ptr), value :: evaluator
      real(c_double), intent(in) :: a_xy(*), a_pose(3), b_xy(*), b_pose(3)
      integer(c_int32_t), value :: a_count, b_count
      type(rockcontact_pair_result), intent(out) :: result
      integer(c_int) :: code
    end function

    function rockcontact_intersection_polygon(evaluator, xy, capacity, count) result(code) &
        bind(C, name="rockcontact_intersection_polygon")
      import :: c_ptr, c_int, c_int32_t, c_double
      type(c_ptr), value :: evaluator
      real(c_double), intent(out) :: xy(*)
      integer(c_int32_t), value :: capacity
      integer(c_int32_t), intent(out) :: count
      integer(c_int) :: code
    end function

    subroutine rockcontact_default_friction_params(params) &
        bind(C, name="rockcontact_default_friction_params")
      import :: rockcontact_friction_params
      type(rockcontact_friction_params), intent(out) :: params
    end subroutine

    function rockcontact_evaluate_friction(params, contact, increment, state, result) &
        result(code) bind(C, name="rockcontact_evaluate_friction")
      import :: rockcontact_friction_params, rockcontact_pair_result, rockcontact_friction_state, &
                rockcontact_friction_result, c_int, c_double
      type(rockcontact_friction_params), intent(in) :: params
      type(rockcontact_pair_result), intent(in) :: contact
      real(c_double), intent(in) :: increment(2)
      type(rockcontact_friction_state), intent(inout) :: state
      type(rockcontact_friction_result), intent(out) :: result
      integer(c_int) :: code
    end function

    subroutine rockcontact_default_params3d(params) bind(C, name="rockcontact_default_params3d")
      import :: rockcontact_params3d
      type(rockcontact_params3d), intent(out) :: params
    end subroutine

    function rockcontact_evaluator3d_create(params, evaluator) result(code) &
        bind(C, name="rockcontact_evaluator3d_create")
      import :: rockcontact_params3d, c_ptr, c_int
      type(rockcontact_params3d), intent(in) :: params
      type(c_ptr), intent(out) :: evaluator
      integer(c_int) :: code
    end function

    subroutine rockcontact_evaluator3d_destroy(evaluator) bind(C, name="rockcontact_evaluator3d_destroy")
      import :: c_ptr
      type(c_ptr), value :: evaluator
    end subroutine

    function rockcontact_evaluate_pair3d(evaluator, a_xyz, a_count, a_face_sizes, a_faces, &
                                         a_face_count, b_xyz, b_count, b_face_sizes, b_faces, &
                                         b_face_count, result) result(code) &
        bind(C, name="rockcontact_evaluate_pair3d")
      import :: rockcontact_pair3d_result, c_ptr, c_int, c_int32_t, c_double
      type(c_ptr), value :: evaluator
      real(c_double), intent(in) :: a_xyz(*), b_xyz(*)
      integer(c_int32_t), intent(in) :: a_face_sizes(*), a_faces(*), b_face_sizes(*), b_faces(*)
      integer(c_int32_t), value :: a_count, a_face_count, b_count, b_face_count
      type(rockcontact_pair3d_result), intent(out) :: result
      integer(c_int) :: code
    end function

    function rockcontact_pair3d_constraints(evaluator, constraints, capacity, count) result(code) &
        bind(C, name="rockcontact_pair3d_constraints")
      import :: rockcontact_constraint3d, c_ptr, c_int, c_int32_t
      type(c_ptr), value :: evaluator
      type(rockcontact_constraint3d), intent(out) :: constraints(*)
      integer(c_int32_t), value :: capacity
      integer(c_int32_t), intent(out) :: count
      integer(c_int) :: code
    end function

    function rockcontact_pair3d_contact_set(evaluator, xyz, capacity, count) result(code) &
        bind(C, name="rockcontact_pair3d_contact_set")
      import :: c_ptr, c_int, c_int32_t, c_double
      type(c_ptr), value :: evaluator
      real(c_double), intent(out) :: xyz(*)
      integer(c_int32_t), value :: capacity
      integer(c_int32_t), intent(out) :: count
      integer(c_int) :: code
    end function

    function c_last_error() result(message) bind(C, name="rockcontact_last_error")
      import :: c_ptr
      type(c_ptr) :: message
    end function

    function c_version() result(version) bind(C, name="rockcontact_version")
      import :: c_ptr
      type(c_ptr) :: version
    end function
  end interface

contains

  ! The message of the last failed call on this thread, as a Fortran string.
  function rockcontact_last_error() result(message)
    character(len=:), allocatable :: message
    message = from_c_string(c_last_error())
  end function

  function rockcontact_version() result(version)
    character(len=:), allocatable :: version
    version = from_c_string(c_version())
  end function

  function from_c_string(pointer) result(text)
    type(c_ptr), intent(in) :: pointer
    character(len=:), allocatable :: text
    character(kind=c_char), pointer :: chars(:)
    integer :: n
    n = 0
    if (c_associated(pointer)) then
      call c_f_pointer(pointer, chars, [huge(0)])
      do while (chars(n + 1) /= c_null_char)
        n = n + 1
      end do
    end if
    allocate(character(len=n) :: text)
    if (n > 0) text = transfer(chars(1:n), text)
  end function

end module rockcontact
