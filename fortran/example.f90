! example.f90: P(gamma, alpha), a curve, a 3-D sphere-sphere rebound and an error, from an export
! of a table, in Fortran through the module oblique_eval (fortran/oblique_eval.f90):
!
!   target/release/sweep export tables/full.h5 -o full.oblq --gamma 1.7497858600774299
!   gcc -std=c99 -O2 -I include -c fortran/oblique_eval_f.c
!   gfortran -std=f2008 -O2 -c fortran/oblique_eval.f90
!   gfortran -std=f2008 -O2 -o example fortran/example.f90 oblique_eval.o oblique_eval_f.o
!   ./example full.oblq
!
! Reals are printed with 17 significant digits (G0.17), which read back to the same double.
! Exit status: 0; 1 (error stop) when the export cannot be opened, or without an argument
! (gfortran then also prints a backtrace: compile with -fno-backtrace, or run with
! GFORTRAN_ERROR_BACKTRACE=0, to leave it out).
program example
   use, intrinsic :: iso_fortran_env, only: error_unit
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
   use oblique_eval
   implicit none

   ! 17 significant digits, no padding (G0.17): every real reads back to the same double.
   character(len=*), parameter :: csv_fmt = '(G0.17,",",G0.17,",",G0.17)'
   character(len=*), parameter :: vec_fmt = '(A,3(1X,G0.17))'
   real(c_double), parameter :: pi = 4*atan(1.0_c_double)
   type(oblique_table) :: table
   type(oblique_curve) :: curve
   character(len=:), allocatable :: path
   integer :: length, k
   integer(c_int) :: status, n_curves
   real(c_double) :: gamma_min, gamma_max, alpha_max, error_bound, found_gamma
   real(c_double) :: inf, p, gammas(3), alphas(3), ps(3)
   integer(c_int) :: statuses(3)
   ! The rebound: two steel spheres.
   real(c_double), parameter :: e_steel = 210.0e9_c_double, nu_steel = 0.29_c_double
   real(c_double), parameter :: rho = 7850.0_c_double, kappa = 0.4_c_double, mu = 0.3_c_double
   real(c_double), parameter :: r1 = 5.0e-3_c_double, r2 = 3.0e-3_c_double
   real(c_double) :: m1, m2, gamma, e_t, energy_lost, alpha
   real(c_double) :: v1(3), w1(3), v2(3), w2(3), normal(3)
   real(c_double) :: v1_after(3), w1_after(3), v2_after(3), w2_after(3)

   if (command_argument_count() < 1) then
      write (error_unit, '(A)') 'usage: example EXPORT   (an export of `sweep export`)'
      error stop 1
   end if
   call get_command_argument(1, length=length)
   allocate (character(len=length) :: path)
   call get_command_argument(1, path)

   call oblique_open(table, path, status)
   if (status /= OBLQ_OK) then
      ! error stop with this text needs Fortran 2018 (a non-constant stop code): print it first.
      write (error_unit, '(A,I0,2A)') 'error: cannot open '//path//': status ', status, ': ', &
         oblique_message(status)
      error stop 1
   end if
   call oblique_info(table, status, gamma_min, gamma_max, alpha_max, error_bound, &
                     n_curves=n_curves)
   write (*, '(A,G0.17,A,G0.17,A,G0.17)') '# domain gamma ', gamma_min, ' to ', gamma_max, &
      ', alpha up to ', alpha_max
   write (*, '(A,ES10.3,A,I0)') '# error bound ', error_bound, ', curves ', n_curves

   ! P(gamma, alpha): elemental, so an array of points in one call.
   inf = ieee_value(inf, ieee_positive_inf)
   gammas = [1.754_c_double, 2.0_c_double, 1.75_c_double]
   alphas = [0.3_c_double, inf, 0.1_c_double]
   call oblique_p(table, gammas, alphas, ps, statuses)
   write (*, '(A)') 'gamma,alpha,P'
   do k = 1, 3
      if (statuses(k) /= OBLQ_OK) then
         write (error_unit, '(A,I0,2A)') 'error: status ', statuses(k), ': ', &
            oblique_message(statuses(k))
         error stop 1
      end if
      write (*, csv_fmt) gammas(k), alphas(k), ps(k)
   end do

   ! A curve of the export (exported with --gamma), if there is one near 1.75.
   call oblique_curve_find(table, 1.75_c_double, curve, status, rel_tol=1.0e-3_c_double, &
                           found_gamma=found_gamma)
   if (status == OBLQ_OK) then
      call oblique_curve_p(curve, 0.3_c_double, p, status)
      write (*, '(A)') 'curve gamma,alpha,P'
      write (*, csv_fmt) found_gamma, 0.3_c_double, p
   else
      write (*, '(2A)') '# no curve: ', oblique_message(status)
   end if
   call oblique_curve_free(curve)

   ! Two steel spheres: 5 mm at (1, 0.2, -2) m/s spinning (0, 50, 0) rad/s hits a 3 mm one at
   ! (0, 0, 1) m/s spinning (0, 0, 10) rad/s; the normal (0, 0, -1) points from sphere 1's
   ! centre to sphere 2's, and (v1 - v2).n = 3 m/s > 0: they approach.
   m1 = rho*(4.0_c_double/3.0_c_double)*pi*r1**3
   m2 = rho*(4.0_c_double/3.0_c_double)*pi*r2**3
   call oblique_gamma_of(m1, r1, kappa, e_steel, nu_steel, m2, r2, kappa, e_steel, nu_steel, &
                         gamma, status)
   if (status /= OBLQ_OK) error stop 'gamma_of failed'
   v1 = [1.0_c_double, 0.2_c_double, -2.0_c_double]
   w1 = [0.0_c_double, 50.0_c_double, 0.0_c_double]
   v2 = [0.0_c_double, 0.0_c_double, 1.0_c_double]
   w2 = [0.0_c_double, 0.0_c_double, 10.0_c_double]
   normal = [0.0_c_double, 0.0_c_double, -1.0_c_double]
   call oblique_rebound_3d(table, m1, r1, kappa, m2, r2, kappa, gamma, mu, v1, w1, v2, w2, &
                           normal, v1_after, w1_after, v2_after, w2_after, p, e_t, &
                           energy_lost, status, alpha=alpha)
   if (status /= OBLQ_OK) then
      write (error_unit, '(A,I0,2A)') 'error: rebound: status ', status, ': ', &
         oblique_message(status)
      error stop 1
   end if
   write (*, '(A)') 'rebound of two steel spheres'
   write (*, '(A,2(1X,G0.17))') 'masses', m1, m2
   write (*, vec_fmt) 'gamma', gamma
   write (*, vec_fmt) 'alpha', alpha
   write (*, vec_fmt) 'v1', v1_after
   write (*, vec_fmt) 'w1', w1_after
   write (*, vec_fmt) 'v2', v2_after
   write (*, vec_fmt) 'w2', w2_after
   write (*, vec_fmt) 'P', p
   write (*, vec_fmt) 'e_t', e_t
   write (*, vec_fmt) 'energy_lost', energy_lost

   ! An error: gamma = -1 is refused with its status and message (and P = NaN).
   call oblique_p(table, -1.0_c_double, 0.3_c_double, p, status)
   write (*, '(A,I0,2A)') 'error at gamma=-1: status ', status, ': ', oblique_message(status)

   call oblique_close(table)
   deallocate (path)
end program example
