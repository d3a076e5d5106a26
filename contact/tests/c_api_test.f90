! The C API from Fortran through the iso_c_binding module rockcontact.f90: the closed form
! "corner" of potential_contact_test.cpp (CP = [0,2]x[0,1], TP = [1.25,4]x[0.25,2]: force
! kn/H (-1/2, -7/16), contact point (369/226, 557/904), IP area 9/16, penetration 0.75; 1e-12
! relative, since the dyadic inputs leave only the integration's roundings) and its intersection
! polygon under every policy, and a refused clockwise polygon with its message. Stops with a non-zero code on a failure.
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

  do policy = ROCKCONTACT_POLICY_FLOAT, ROCKCONTACT_POLICY_EXACT
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

  if (failures > 0) error stop 1
  print '(a)', 'c_api_test (Fortran): all checks passed'

contains

  logical function close_to(actual, expected)
    real(c_double), intent(in) :: actual, expected
    close_to = abs(actual - expected) <= 1.0e-12_c_double * abs(expected)
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
