! The C API from Fortran through the iso_c_binding module rockcontact.f90: the closed form
! "corner" of potential_contact_test.cpp (CP = [0,2]x[0,1], TP = [1.25,4]x[0.25,2]: force
! kn/H (-1/2, -7/16), contact point (369/226, 557/904), IP area 9/16, penetration 0.75; 1e-12
! relative, since the dyadic inputs leave only the integration's roundings) and its intersection
! polygon under every policy, and a refused clockwise polygon with its message. Then friction:
! a 1 m square pressed d = 2^-10 m into a 4 m x 1 m base (normal force kn (2 d - d^2) / H, contact
! length 1 + d: closed forms, see pair_friction_test.cpp) pushed along the face by 2^-13 m steps:
! stick at -kt push, slide at F tan 30 deg dissipating limit x push, reset on separation, a
! refused kt; to 1e-10 relative (a handful of roundings on the 1e-12 force). Then 3D: a 0.5 m
! cube pressed d = 2^-10 m into a unit cube (dyadic coordinates: exact or one rounding off):
! overlap, volume d/4, depth d upwards, four vertex-face constraints with gap -d and force kn d.
! Stops with a non-zero code on a failure.
program c_api_test
  use, intrinsic :: iso_c_binding, only: c_ptr, c_double, c_int, c_int32_t
  use rockcontact
  implicit none

  real(c_double), parameter :: kn = 2.0e7_c_double, H = 0.5_c_double
  real(c_double), parameter :: a_xy(8) = [-1.0_c_double, -0.5_c_double, 1.0_c_double, -0.5_c_double, &
                                          1.0_c_double, 0.5_c_double, -1.0_c_double, 0.5_c_double]
  real(c_double), parameter :: b_xy(8) = [-1.375_c_double, -0.875_c_double, 1.375_c_double, &
                                          -0.875_c_double, 1.375_c_double, 0.875_c_double, &
                                          -1.375_c_double, 0.875_c_double]
  real(c_double), parameter :: a_pose(3) = [1.0_c_double, 0.5_c_double, 0.0_c_double]
  real(c_double), parameter :: b_pose(3) = [2.625_c_double, 1.125_c_double, 0.0_c_double]
  real(c_double), parameter :: clockwise(8) = [0.0_c_double, 0.0_c_double, 0.0_c_double, &
                                               1.0_c_double, 1.0_c_double, 1.0_c_double, &
                                               1.0_c_double, 0.0_c_double]
  type(rockcontact_params) :: params
  type(rockcontact_pair_result) :: r
  type(c_ptr) :: contact
  integer(c_int32_t) :: policy, ip_count
  real(c_double) :: ip(8)
  integer :: failures = 0
  real(c_double) :: scale

  scale = kn / H
  call rockcontact_default_params(params)
  call check(params%policy == ROCKCONTACT_POLICY_FILTERED .and. params%kn == 1.0e7_c_double, &
             'default parameters')
  call check(len(rockcontact_version()) >= 5, 'version string')
  params%kn = kn
  params%H = H

  do policy = ROCKCONTACT_POLICY_FLOAT, ROCKCONTACT_POLICY_CHECKED
    params%policy = policy
    call check(rockcontact_evaluator_create(params, contact) == ROCKCONTACT_OK, 'create')
    call check(rockcontact_evaluate_pair(contact, a_xy, 4_c_int32_t, a_pose, b_xy, 4_c_int32_t, &
                                         b_pose, r) == ROCKCONTACT_OK, 'evaluate the corner pair')
    call check(r%status == ROCKCONTACT_OVERLAP .and. r%has_point == 1, 'corner: overlap with a point')
    call check(close_to(r%area, 9.0_c_double / 16.0_c_double), 'corner: area 9/16')
    call check(close_to(r%force(1), -0.5_c_double * scale) .and. &
               close_to(r%force(2), -7.0_c_double / 16.0_c_double * scale), 'corner: force')
    call check(close_to(r%point(1), 369.0_c_double / 226.0_c_double) .and. &
               close_to(r%point(2), 557.0_c_double / 904.0_c_double), 'corner: point')
    call check(close_to(r%penetration, 0.75_c_double), 'corner: penetration 0.75')
    call check(rockcontact_intersection_polygon(contact, ip, 4_c_int32_t, ip_count) == ROCKCONTACT_OK &
               .and. ip_count == 4, 'corner: IP of 4 vertices')
    call check(all(ip(1::2) == 1.25_c_double .or. ip(1::2) == 2.0_c_double) .and. &
               all(ip(2::2) == 0.25_c_double .or. ip(2::2) == 1.0_c_double), &
               'corner: IP = [1.25, 2] x [0.25, 1]')
    if (policy == ROCKCONTACT_POLICY_FILTERED) then
      call check(rockcontact_evaluate_pair(contact, clockwise, 4_c_int32_t, a_pose, b_xy, &
                                           4_c_int32_t, b_pose, r) == ROCKCONTACT_ERROR_INVALID_POLYGON, &
                 'clockwise polygon refused')
      call check(index(rockcontact_last_error(), 'polygon a') > 0 .and. &
                 index(rockcontact_last_error(), 'counter-clockwise') > 0, 'message names polygon a')
    end if
    call rockcontact_evaluator_destroy(contact)
  end do

  call check_friction()
  call check_3d()

  if (failures > 0) error stop 1
  print '(a)', 'c_api_test (Fortran): all checks passed'

contains

  logical function close_to(actual, expected)
    real(c_double), intent(in) :: actual, expected
    close_to = abs(actual - expected) <= 1.0e-12_c_double * abs(expected)
  end function

  subroutine check_friction()
    real(c_double), parameter :: d = 1.0_c_double / 1024.0_c_double
    real(c_double), parameter :: push = 1.0_c_double / 8192.0_c_double
    real(c_double), parameter :: block(8) = [-0.5_c_double, -0.5_c_double, 0.5_c_double, &
                                             -0.5_c_double, 0.5_c_double, 0.5_c_double, &
                                             -0.5_c_double, 0.5_c_double]
    real(c_double), parameter :: base(8) = [-2.0_c_double, -0.5_c_double, 2.0_c_double, &
                                            -0.5_c_double, 2.0_c_double, 0.5_c_double, &
                                            -2.0_c_double, 0.5_c_double]
    real(c_double), parameter :: base_pose(3) = 0.0_c_double, step(2) = [push, 0.0_c_double]
    type(rockcontact_params) :: params
    type(rockcontact_friction_params) :: friction, bad
    type(rockcontact_friction_state) :: state
    type(rockcontact_friction_result) :: t
    type(rockcontact_pair_result) :: r
    type(c_ptr) :: contact
    real(c_double) :: fn, limit, pose(3)
    integer(c_int) :: code
    integer :: k

    fn = 1.0e7_c_double * (2.0_c_double * d - d * d)
    limit = fn * tan(acos(-1.0_c_double) / 6.0_c_double)
    call rockcontact_default_params(params)
    params%kn = 1.0e7_c_double
    call check(rockcontact_evaluator_create(params, contact) == ROCKCONTACT_OK, 'friction: create')
    call rockcontact_default_friction_params(friction)
    call check(friction%kt == 1.0e7_c_double .and. friction%model == ROCKCONTACT_FRICTION_ELASTOPLASTIC, &
               'default friction parameters')
    friction%friction_angle_deg = 30.0_c_double
    ! One call per statement: Fortran may evaluate the operands of .and. in any order, so a
    ! result must not be read in the expression that produces it.
    do k = 0, 11
      pose = [k * push, 1.0_c_double - d, 0.0_c_double]
      code = rockcontact_evaluate_pair(contact, block, 4_c_int32_t, pose, base, 4_c_int32_t, &
                                       base_pose, r)
      call check(code == ROCKCONTACT_OK .and. r%has_point == 1, 'friction: pressed block in contact')
      call check(near(r%force(2), fn, fn) .and. near(r%length, 1.0_c_double + d, 1.0_c_double), &
                 'friction: F = kn (2 d - d^2) / H, L = 1 + d')
      call check(rockcontact_evaluate_friction(friction, r, step, state, t) == ROCKCONTACT_OK, &
                 'friction: evaluate')
      if (k == 1) call check(near(t%force(1), -friction%kt * push, limit) .and. t%sliding == 0, &
                             'friction: stick at -kt push')
      if (k == 11) call check(near(t%force(1), -limit, limit) .and. t%sliding == 1 .and. &
                              near(t%dissipated, limit * push, limit * push), &
                              'friction: slide at F tan 30, dissipating limit x push')
    end do
    bad = friction
    bad%kt = -1.0_c_double
    code = rockcontact_evaluate_friction(bad, r, step, state, t)
    call check(code == ROCKCONTACT_ERROR_INVALID_ARGUMENT .and. &
               index(rockcontact_last_error(), 'kt must be finite and > 0') > 0, &
               'friction: negative kt refused')
    call check(state%sliding == 1 .and. state%in_contact == 1, 'friction: a refusal leaves the state')
    pose = [0.0_c_double, 1.0_c_double + d, 0.0_c_double]
    code = rockcontact_evaluate_pair(contact, block, 4_c_int32_t, pose, base, 4_c_int32_t, &
                                     base_pose, r)
    call check(code == ROCKCONTACT_OK .and. r%has_point == 0, 'friction: lifted block separates')
    code = rockcontact_evaluate_friction(friction, r, step, state, t)
    call check(code == ROCKCONTACT_OK .and. all(t%force == 0.0_c_double) .and. state%in_contact == 0 .and. &
               all(state%displacement == 0.0_c_double), 'friction: separation resets the state')
    call rockcontact_evaluator_destroy(contact)
  end subroutine

  subroutine check_3d()
    real(c_double), parameter :: d = 1.0_c_double / 1024.0_c_double
    real(c_double) :: a_xyz(24), b_xyz(24)
    integer(c_int32_t), parameter :: sizes(6) = [4, 4, 4, 4, 4, 4]
    integer(c_int32_t), parameter :: faces(24) = [0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, &
                                                  2, 3, 7, 6, 3, 0, 4, 7]
    type(rockcontact_params3d) :: params3
    type(rockcontact_pair3d_result) :: r3
    type(rockcontact_constraint3d) :: c(8)
    type(c_ptr) :: contact3
    integer(c_int32_t) :: count
    integer :: k
    a_xyz = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1]
    do k = 0, 7
      b_xyz(3 * k + 1) = 0.25_c_double + 0.5_c_double * a_xyz(3 * k + 1)
      b_xyz(3 * k + 2) = 0.25_c_double + 0.5_c_double * a_xyz(3 * k + 2)
      b_xyz(3 * k + 3) = 1.0_c_double - d + 0.5_c_double * a_xyz(3 * k + 3)
    end do
    call rockcontact_default_params3d(params3)
    call check(params3%kn == 1.0e9_c_double .and. params3%policy == ROCKCONTACT_POLICY_FILTERED, &
               '3d: default parameters')
    call check(rockcontact_evaluator3d_create(params3, contact3) == ROCKCONTACT_OK, '3d: create')
    call check(rockcontact_evaluate_pair3d(contact3, a_xyz, 8_c_int32_t, sizes, faces, 6_c_int32_t, &
                                           b_xyz, 8_c_int32_t, sizes, faces, 6_c_int32_t, r3) &
               == ROCKCONTACT_OK, '3d: evaluate')
    call check(r3%status == ROCKCONTACT_OVERLAP .and. close_to(r3%volume, 0.25_c_double * d) .and. &
               close_to(r3%depth, d) .and. r3%normal(3) == 1.0_c_double, '3d: volume d/4, depth d up')
    call check(rockcontact_pair3d_constraints(contact3, c, 8_c_int32_t, count) == ROCKCONTACT_OK &
               .and. count == 4 .and. r3%constraint_count == 4, '3d: four constraints')
    do k = 1, 4
      call check(c(k)%type == ROCKCONTACT_VERTEX_FACE .and. close_to(c(k)%gap, -d) .and. &
                 close_to(c(k)%force(3), params3%kn * d), '3d: vertex-face, gap -d, force kn d')
    end do
    call rockcontact_evaluator3d_destroy(contact3)
  end subroutine

  logical function near(actual, expected, scale)
    real(c_double), intent(in) :: actual, expected, scale
    near = abs(actual - expected) <= 1.0e-10_c_double * scale
  end function

  subroutine check(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what
    if (.not. ok) then
      failures = failures + 1
      print '(2a)', 'FAILED: ', what
    end if
  end subroutine

end program c_api_test
