! oblique_eval.f90: Fortran 2008 bindings of the dependency-free evaluator include/oblique_eval.h,
! through the C shim fortran/oblique_eval_f.c (iso_c_binding). P(gamma, alpha) (P(gamma, alpha,
! e_n) of a table with a normal-restitution axis), curves P(alpha) of one gamma, and 3-D rebounds of spheres on walls and spheres, from an export of a table
! (`sweep export TABLE -o FILE`). Symbols and units (SI) as in the header and ../shared/physics.md.
!
!   gcc -std=c99 -O2 -I include -c fortran/oblique_eval_f.c
!   gfortran -std=f2008 -O2 -c fortran/oblique_eval.f90
!   gfortran -std=f2008 -O2 -o example fortran/example.f90 oblique_eval.o oblique_eval_f.o
!
!   use oblique_eval
!   type(oblique_table) :: t
!   call oblique_open(t, 'full.oblq', status)        ! reads and checks the export once
!   if (status /= OBLQ_OK) error stop                ! oblique_message(status): the reason
!   call oblique_p(t, 1.754_c_double, 0.3_c_double, p, status)
!   call oblique_close(t)
!
! Every procedure reports an integer(c_int) status: OBLQ_OK (0) or one of the OBLQ_E_* codes
! below (the values of the header's enum, plus OBLQF_E_IO, OBLQF_E_NOMEM and
! OBLQF_E_NOT_FILE of the shim);
! oblique_message(status) is its text. On an error the real outputs are NaN.
!
! Tables and curves hold C memory: release them with oblique_close and oblique_curve_free
! (curves before their table: a curve points into its table). Opening or finding into a
! variable that still holds one releases the old one first. Copies of an oblique_table or
! oblique_curve share the memory (release it once). Once made they are read-only and may be
! used by several threads (OpenMP) at once.
module oblique_eval
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_ptr, c_null_ptr, &
                                          c_null_char, c_associated
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   implicit none
   private

   public :: c_int, c_double
   public :: oblique_table, oblique_curve
   public :: oblique_open, oblique_close, oblique_info, oblique_p, oblique_p_e
   public :: oblique_p_at, oblique_axis_count, oblique_axis_name
   public :: oblique_e_n_range
   public :: oblique_curve_find, oblique_curve_p, oblique_curve_free
   public :: oblique_rebound_3d, oblique_rebound_3d_curve, oblique_gamma_of, oblique_message

   ! Status codes: the values of the OBLQ_* enum of include/oblique_eval.h.
   integer(c_int), parameter, public :: OBLQ_OK = 0
   integer(c_int), parameter, public :: OBLQ_E_NULL = 1          ! a handle is not open
   integer(c_int), parameter, public :: OBLQ_E_TRUNCATED = 2     ! the export is truncated
   integer(c_int), parameter, public :: OBLQ_E_FORMAT = 3        ! not an export (magic bytes)
   integer(c_int), parameter, public :: OBLQ_E_VERSION = 4       ! another layout version
   integer(c_int), parameter, public :: OBLQ_E_CHECKSUM = 5      ! damaged: checksum mismatch
   integer(c_int), parameter, public :: OBLQ_E_CORRUPT = 6       ! inconsistent contents
   integer(c_int), parameter, public :: OBLQ_E_GAMMA = 7         ! gamma not finite or <= 0
   integer(c_int), parameter, public :: OBLQ_E_ALPHA = 8         ! alpha NaN or < 0
   integer(c_int), parameter, public :: OBLQ_E_GAMMA_DOMAIN = 9  ! gamma outside the domain
   integer(c_int), parameter, public :: OBLQ_E_ALPHA_DOMAIN = 10 ! alpha above alpha_max
   integer(c_int), parameter, public :: OBLQ_E_NO_SURFACE = 11   ! a curves-only export
   integer(c_int), parameter, public :: OBLQ_E_NO_CURVE = 12     ! no curve of that gamma
   integer(c_int), parameter, public :: OBLQ_E_MASS = 13         ! mass not finite or <= 0
   integer(c_int), parameter, public :: OBLQ_E_RADIUS = 14       ! radius not finite or <= 0
   integer(c_int), parameter, public :: OBLQ_E_KAPPA = 15        ! kappa not finite or <= 0
   integer(c_int), parameter, public :: OBLQ_E_FRICTION = 16     ! friction NaN or < 0
   integer(c_int), parameter, public :: OBLQ_E_MODULUS = 17      ! Young's modulus invalid
   integer(c_int), parameter, public :: OBLQ_E_POISSON = 18      ! Poisson's ratio invalid
   integer(c_int), parameter, public :: OBLQ_E_MOTION = 19       ! a vector component not finite
   integer(c_int), parameter, public :: OBLQ_E_NORMAL = 20       ! a zero normal
   integer(c_int), parameter, public :: OBLQ_E_APPROACH = 21     ! the bodies do not approach
   integer(c_int), parameter, public :: OBLQ_E_WALL_MOTION = 22  ! a wall given a motion
   integer(c_int), parameter, public :: OBLQ_E_P_RANGE = 23      ! P outside [-1, 1]
   integer(c_int), parameter, public :: OBLQ_E_KAPPA_P = 23      ! deprecated: OBLQ_E_P_RANGE
   integer(c_int), parameter, public :: OBLQ_E_E_N = 24          ! e_n outside the table's range
   integer(c_int), parameter, public :: OBLQ_E_AXES = 28         ! a point of another size
   ! The codes of the header's file loader oblq_load_file (the module reads files through the
   ! shim, whose codes are the OBLQF_E_* below).
   integer(c_int), parameter, public :: OBLQ_E_FILE = 25         ! the file cannot be read
   integer(c_int), parameter, public :: OBLQ_E_NOT_FILE = 26     ! not a regular file
   integer(c_int), parameter, public :: OBLQ_E_NO_MEMORY = 27    ! out of memory
   ! Codes of the shim fortran/oblique_eval_f.c.
   integer(c_int), parameter, public :: OBLQF_E_IO = 101         ! the file cannot be read
   integer(c_int), parameter, public :: OBLQF_E_NOMEM = 102      ! out of memory
   integer(c_int), parameter, public :: OBLQF_E_NOT_FILE = 103   ! not a regular file

   !> An export read into memory and checked (oblique_open); release with oblique_close.
   type :: oblique_table
      type(c_ptr) :: handle = c_null_ptr
   end type oblique_table

   !> P(alpha) at one exported gamma (oblique_curve_find); release with oblique_curve_free.
   type :: oblique_curve
      type(c_ptr) :: handle = c_null_ptr
   end type oblique_curve

   interface
      integer(c_int) function oblqf_open(path, handle) bind(C, name='oblqf_open')
         import :: c_int, c_char, c_ptr
         character(kind=c_char), intent(in) :: path(*)
         type(c_ptr), intent(out) :: handle
      end function oblqf_open

      subroutine oblqf_close(handle) bind(C, name='oblqf_close')
         import :: c_ptr
         type(c_ptr), value :: handle
      end subroutine oblqf_close

      integer(c_int) function oblqf_info(handle, gamma_min, gamma_max, alpha_max, &
                                         error_bound, has_surface, n_curves) &
         bind(C, name='oblqf_info')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: handle
         real(c_double), intent(out) :: gamma_min, gamma_max, alpha_max, error_bound
         integer(c_int), intent(out) :: has_surface, n_curves
      end function oblqf_info

      integer(c_int) function oblqf_p(handle, gamma, alpha, clamp, p) bind(C, name='oblqf_p')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: handle
         real(c_double), value :: gamma, alpha
         integer(c_int), value :: clamp
         real(c_double), intent(out) :: p
      end function oblqf_p

      integer(c_int) function oblqf_p_e(handle, gamma, alpha, e_n, clamp, p) &
         bind(C, name='oblqf_p_e')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: handle
         real(c_double), value :: gamma, alpha, e_n
         integer(c_int), value :: clamp
         real(c_double), intent(out) :: p
      end function oblqf_p_e

      integer(c_int) function oblqf_p_at(handle, x, n, clamp, p) bind(C, name='oblqf_p_at')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: handle
         real(c_double), intent(in) :: x(*)
         integer(c_int), value :: n, clamp
         real(c_double), intent(out) :: p
      end function oblqf_p_at

      integer(c_int) function oblqf_axis_count(handle, n) bind(C, name='oblqf_axis_count')
         import :: c_int, c_ptr
         type(c_ptr), value :: handle
         integer(c_int), intent(out) :: n
      end function oblqf_axis_count

      integer(c_int) function oblqf_axis_name(handle, i, name, cap, length) &
         bind(C, name='oblqf_axis_name')
         import :: c_int, c_char, c_ptr
         type(c_ptr), value :: handle
         integer(c_int), value :: i, cap
         character(kind=c_char), intent(out) :: name(*)
         integer(c_int), intent(out) :: length
      end function oblqf_axis_name

      integer(c_int) function oblqf_e_n_range(handle, e_n_min, e_n_max) &
         bind(C, name='oblqf_e_n_range')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: handle
         real(c_double), intent(out) :: e_n_min, e_n_max
      end function oblqf_e_n_range

      integer(c_int) function oblqf_curve_find(handle, gamma, rel_tol, curve, found_gamma) &
         bind(C, name='oblqf_curve_find')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: handle
         real(c_double), value :: gamma, rel_tol
         type(c_ptr), intent(out) :: curve
         real(c_double), intent(out) :: found_gamma
      end function oblqf_curve_find

      subroutine oblqf_curve_free(curve) bind(C, name='oblqf_curve_free')
         import :: c_ptr
         type(c_ptr), value :: curve
      end subroutine oblqf_curve_free

      integer(c_int) function oblqf_curve_p(curve, alpha, clamp, p) &
         bind(C, name='oblqf_curve_p')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: curve
         real(c_double), value :: alpha
         integer(c_int), value :: clamp
         real(c_double), intent(out) :: p
      end function oblqf_curve_p

      integer(c_int) function oblqf_rebound_3d(handle, m1, r1, kappa1, m2, r2, kappa2, &
                                               gamma, mu, v1, w1, v2, w2, normal, clamp, &
                                               v1_out, w1_out, v2_out, w2_out, p, alpha, &
                                               e_t, energy_lost) &
         bind(C, name='oblqf_rebound_3d')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: handle
         real(c_double), value :: m1, r1, kappa1, m2, r2, kappa2, gamma, mu
         real(c_double), intent(in) :: v1(3), w1(3), v2(3), w2(3), normal(3)
         integer(c_int), value :: clamp
         real(c_double), intent(out) :: v1_out(3), w1_out(3), v2_out(3), w2_out(3)
         real(c_double), intent(out) :: p, alpha, e_t, energy_lost
      end function oblqf_rebound_3d

      integer(c_int) function oblqf_rebound_3d_e(handle, m1, r1, kappa1, m2, r2, kappa2, &
                                                 gamma, mu, e_n, v1, w1, v2, w2, normal, &
                                                 clamp, v1_out, w1_out, v2_out, w2_out, p, &
                                                 alpha, e_t, energy_lost) &
         bind(C, name='oblqf_rebound_3d_e')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: handle
         real(c_double), value :: m1, r1, kappa1, m2, r2, kappa2, gamma, mu, e_n
         real(c_double), intent(in) :: v1(3), w1(3), v2(3), w2(3), normal(3)
         integer(c_int), value :: clamp
         real(c_double), intent(out) :: v1_out(3), w1_out(3), v2_out(3), w2_out(3)
         real(c_double), intent(out) :: p, alpha, e_t, energy_lost
      end function oblqf_rebound_3d_e

      integer(c_int) function oblqf_rebound_3d_curve(curve, m1, r1, kappa1, m2, r2, kappa2, &
                                                     mu, v1, w1, v2, w2, normal, clamp, &
                                                     v1_out, w1_out, v2_out, w2_out, p, &
                                                     alpha, e_t, energy_lost) &
         bind(C, name='oblqf_rebound_3d_curve')
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: curve
         real(c_double), value :: m1, r1, kappa1, m2, r2, kappa2, mu
         real(c_double), intent(in) :: v1(3), w1(3), v2(3), w2(3), normal(3)
         integer(c_int), value :: clamp
         real(c_double), intent(out) :: v1_out(3), w1_out(3), v2_out(3), w2_out(3)
         real(c_double), intent(out) :: p, alpha, e_t, energy_lost
      end function oblqf_rebound_3d_curve

      integer(c_int) function oblqf_gamma_of(m1, r1, kappa1, m2, r2, kappa2, e1, nu1, e2, &
                                             nu2, gamma) bind(C, name='oblqf_gamma_of')
         import :: c_int, c_double
         real(c_double), value :: m1, r1, kappa1, m2, r2, kappa2, e1, nu1, e2, nu2
         real(c_double), intent(out) :: gamma
      end function oblqf_gamma_of

      integer(c_int) function oblqf_message(code, buf, cap) bind(C, name='oblqf_message')
         import :: c_int, c_char
         integer(c_int), value :: code
         character(kind=c_char), intent(out) :: buf(*)
         integer(c_int), value :: cap
      end function oblqf_message
   end interface

contains

   !> 1 when clamp is present and true, else 0.
   pure integer(c_int) function clamp_flag(clamp)
      logical, intent(in), optional :: clamp
      clamp_flag = 0_c_int
      if (present(clamp)) then
         if (clamp) clamp_flag = 1_c_int
      end if
   end function clamp_flag

   pure real(c_double) function nan()
      nan = ieee_value(0.0_c_double, ieee_quiet_nan)
   end function nan

   !> Read the export at `path` (trailing blanks ignored) and check it (layout, checksum).
   !> `table` is closed first if it is open; on an error it stays closed.
   subroutine oblique_open(table, path, status)
      type(oblique_table), intent(inout) :: table
      character(len=*), intent(in) :: path
      integer(c_int), intent(out) :: status
      call oblique_close(table)
      status = oblqf_open(trim(path)//c_null_char, table%handle)
   end subroutine oblique_open

   !> Release the memory of a table (a closed table: nothing).
   subroutine oblique_close(table)
      type(oblique_table), intent(inout) :: table
      if (c_associated(table%handle)) call oblqf_close(table%handle)
      table%handle = c_null_ptr
   end subroutine oblique_close

   !> The table's domain [gamma_min, gamma_max] x [0, alpha_max], its absolute error bound on
   !> every P, whether it holds the surface (or only curves) and its number of curves. The
   !> table of one pair (P(alpha, e_n) at a single gamma): gamma_min = gamma_max, its gamma.
   subroutine oblique_info(table, status, gamma_min, gamma_max, alpha_max, error_bound, &
                           has_surface, n_curves)
      type(oblique_table), intent(in) :: table
      integer(c_int), intent(out) :: status
      real(c_double), intent(out), optional :: gamma_min, gamma_max, alpha_max, error_bound
      logical, intent(out), optional :: has_surface
      integer(c_int), intent(out), optional :: n_curves
      real(c_double) :: g0, g1, a1, eb
      integer(c_int) :: surface, n
      status = oblqf_info(table%handle, g0, g1, a1, eb, surface, n)
      if (status /= OBLQ_OK) then
         g0 = nan()
         g1 = nan()
         a1 = nan()
         eb = nan()
         surface = 0
         n = 0
      end if
      if (present(gamma_min)) gamma_min = g0
      if (present(gamma_max)) gamma_max = g1
      if (present(alpha_max)) alpha_max = a1
      if (present(error_bound)) error_bound = eb
      if (present(has_surface)) has_surface = surface /= 0
      if (present(n_curves)) n_curves = n
   end subroutine oblique_info

   !> P(gamma, alpha) by the table's rule, -1 <= P <= 1; alpha = +infinity (ieee_value) for no
   !> slip. Outside the table's domain: OBLQ_E_GAMMA_DOMAIN / OBLQ_E_ALPHA_DOMAIN, or with
   !> clamp = .true. the answer at the nearest point of the domain. Elemental: gamma, alpha,
   !> p and status may be conforming arrays.
   impure elemental subroutine oblique_p(table, gamma, alpha, p, status, clamp)
      type(oblique_table), intent(in) :: table
      real(c_double), intent(in) :: gamma, alpha
      real(c_double), intent(out) :: p
      integer(c_int), intent(out) :: status
      logical, intent(in), optional :: clamp
      status = oblqf_p(table%handle, gamma, alpha, clamp_flag(clamp), p)
      if (status /= OBLQ_OK) p = nan()
   end subroutine oblique_p

   !> P(gamma, alpha, e_n) at normal restitution e_n by the table's rule, -1 <= P <= 1. e_n
   !> must lie in the table's e_n range (oblique_e_n_range), else OBLQ_E_E_N: it is never
   !> clamped, and an elastic table answers e_n = 1 only. gamma, alpha and clamp as for
   !> oblique_p (clamp moves gamma and alpha only); the table of one pair takes a gamma within
   !> 1e-9 (relative) of its own as its own and refuses any other above the full-slip line
   !> (OBLQ_E_GAMMA_DOMAIN), or clamps it to its own. Elemental.
   impure elemental subroutine oblique_p_e(table, gamma, alpha, e_n, p, status, clamp)
      type(oblique_table), intent(in) :: table
      real(c_double), intent(in) :: gamma, alpha, e_n
      real(c_double), intent(out) :: p
      integer(c_int), intent(out) :: status
      logical, intent(in), optional :: clamp
      status = oblqf_p_e(table%handle, gamma, alpha, e_n, clamp_flag(clamp), p)
      if (status /= OBLQ_OK) p = nan()
   end subroutine oblique_p_e

   !> P at the point x, one value per axis of the table in order (oblique_axis_count,
   !> oblique_axis_name: gamma, alpha, and e_n for a table with that axis): oblique_p or
   !> oblique_p_e with the same bits; a point of another size is OBLQ_E_AXES.
   subroutine oblique_p_at(table, x, p, status, clamp)
      type(oblique_table), intent(in) :: table
      real(c_double), intent(in) :: x(:)
      real(c_double), intent(out) :: p
      integer(c_int), intent(out) :: status
      logical, intent(in), optional :: clamp
      real(c_double) :: copy(max(size(x), 1))
      copy = 0
      copy(1:size(x)) = x
      status = oblqf_p_at(table%handle, copy, int(size(x), c_int), clamp_flag(clamp), p)
      if (status /= OBLQ_OK) p = nan()
   end subroutine oblique_p_at

   !> The number of axes of a point of the table (2, or 3 with an e_n axis).
   subroutine oblique_axis_count(table, n, status)
      type(oblique_table), intent(in) :: table
      integer(c_int), intent(out) :: n
      integer(c_int), intent(out) :: status
      status = oblqf_axis_count(table%handle, n)
      if (status /= OBLQ_OK) n = 0
   end subroutine oblique_axis_count

   !> The name of axis i (1-based, as Fortran counts) of a point of the table: 'gamma',
   !> 'alpha', 'e_n'; OBLQ_E_AXES for another i.
   subroutine oblique_axis_name(table, i, name, status)
      type(oblique_table), intent(in) :: table
      integer, intent(in) :: i
      character(len=*), intent(out) :: name
      integer(c_int), intent(out) :: status
      character(kind=c_char) :: buf(max(len(name), 1))
      integer(c_int) :: length
      integer :: k
      status = oblqf_axis_name(table%handle, int(i - 1, c_int), buf, int(len(name), c_int), &
                               length)
      name = ''
      if (status == OBLQ_OK) then
         do k = 1, min(int(length), len(name))
            name(k:k) = buf(k)
         end do
      end if
   end subroutine oblique_axis_name

   !> The e_n range [e_n_min, e_n_max] the table answers (1, 1 for an elastic table).
   subroutine oblique_e_n_range(table, e_n_min, e_n_max, status)
      type(oblique_table), intent(in) :: table
      real(c_double), intent(out) :: e_n_min, e_n_max
      integer(c_int), intent(out) :: status
      status = oblqf_e_n_range(table%handle, e_n_min, e_n_max)
      if (status /= OBLQ_OK) then
         e_n_min = nan()
         e_n_max = nan()
      end if
   end subroutine oblique_e_n_range

   !> The exported curve whose gamma is nearest to `gamma`, if within `rel_tol` relative
   !> (default 0: exactly the exported value; exports hold the curves of `sweep export
   !> --gamma G`). found_gamma: that curve's gamma. `curve` is freed first if it holds one.
   subroutine oblique_curve_find(table, gamma, curve, status, rel_tol, found_gamma)
      type(oblique_table), intent(in) :: table
      real(c_double), intent(in) :: gamma
      type(oblique_curve), intent(inout) :: curve
      integer(c_int), intent(out) :: status
      real(c_double), intent(in), optional :: rel_tol
      real(c_double), intent(out), optional :: found_gamma
      real(c_double) :: tol, g
      tol = 0.0_c_double
      if (present(rel_tol)) tol = rel_tol
      call oblique_curve_free(curve)
      status = oblqf_curve_find(table%handle, gamma, tol, curve%handle, g)
      if (status /= OBLQ_OK) g = nan()
      if (present(found_gamma)) found_gamma = g
   end subroutine oblique_curve_find

   !> Release a curve (a free curve: nothing).
   subroutine oblique_curve_free(curve)
      type(oblique_curve), intent(inout) :: curve
      if (c_associated(curve%handle)) call oblqf_curve_free(curve%handle)
      curve%handle = c_null_ptr
   end subroutine oblique_curve_free

   !> P(alpha) at the curve's gamma (the table's P to about 1e-15, fewer operations). alpha
   !> above alpha_max: OBLQ_E_ALPHA_DOMAIN, or with clamp = .true. P at alpha_max. Elemental.
   impure elemental subroutine oblique_curve_p(curve, alpha, p, status, clamp)
      type(oblique_curve), intent(in) :: curve
      real(c_double), intent(in) :: alpha
      real(c_double), intent(out) :: p
      integer(c_int), intent(out) :: status
      logical, intent(in), optional :: clamp
      status = oblqf_curve_p(curve%handle, alpha, clamp_flag(clamp), p)
      if (status /= OBLQ_OK) p = nan()
   end subroutine oblique_curve_p

   !> NaN in every output (after an error).
   pure subroutine rebound_nan(v1_after, w1_after, v2_after, w2_after, p, e_t, energy_lost, &
                               alpha)
      real(c_double), intent(out) :: v1_after(3), w1_after(3), v2_after(3), w2_after(3)
      real(c_double), intent(out) :: p, e_t, energy_lost, alpha
      v1_after = nan()
      w1_after = nan()
      v2_after = nan()
      w2_after = nan()
      p = nan()
      e_t = nan()
      energy_lost = nan()
      alpha = nan()
   end subroutine rebound_nan

   !> The 3-D rebound of sphere 1 (mass m1 kg, radius r1 m, kappa1 in I = kappa m R^2) on a
   !> wall (m2 = 0: r2 and kappa2 ignored, v2 and w2 must be zero) or on sphere 2, with the
   !> material group gamma (oblique_gamma_of) and friction mu >= 0 (+infinity: no slip); P from
   !> the table. Before: velocities v1, v2 (m/s), spins w1, w2 (rad/s), the normal from
   !> sphere 1's centre into the wall or towards sphere 2's centre (any non-zero length; the
   !> bodies must approach along it). After: v1_after, w1_after, v2_after, w2_after (a wall's
   !> stay zero), P (NaN when the contact point does not slip), e_t (tangential restitution of
   !> the centres; NaN when they have no tangential motion), energy_lost (J), and optionally
   !> alpha (the friction group used; +infinity without slip). Optional e_n (default 1, elastic):
   !> the normal restitution, 0 <= e_n <= 1: the normal relative velocity reverses to e_n times
   !> its value, P is the table's P(gamma, alpha, e_n) (e_n in its range, oblique_e_n_range,
   !> else OBLQ_E_E_N; an elastic table answers e_n = 1 only) and energy_lost adds
   !> (m*/2) v_z0**2 (1 - e_n**2).
   subroutine oblique_rebound_3d(table, m1, r1, kappa1, m2, r2, kappa2, gamma, mu, &
                                 v1, w1, v2, w2, normal, v1_after, w1_after, v2_after, &
                                 w2_after, p, e_t, energy_lost, status, clamp, alpha, e_n)
      type(oblique_table), intent(in) :: table
      real(c_double), intent(in) :: m1, r1, kappa1, m2, r2, kappa2, gamma, mu
      real(c_double), intent(in) :: v1(3), w1(3), v2(3), w2(3), normal(3)
      real(c_double), intent(out) :: v1_after(3), w1_after(3), v2_after(3), w2_after(3)
      real(c_double), intent(out) :: p, e_t, energy_lost
      integer(c_int), intent(out) :: status
      logical, intent(in), optional :: clamp
      real(c_double), intent(out), optional :: alpha
      real(c_double), intent(in), optional :: e_n
      real(c_double) :: a, e
      e = 1.0_c_double
      if (present(e_n)) e = e_n
      status = oblqf_rebound_3d_e(table%handle, m1, r1, kappa1, m2, r2, kappa2, gamma, mu, e, &
                                  v1, w1, v2, w2, normal, clamp_flag(clamp), v1_after, &
                                  w1_after, v2_after, w2_after, p, a, e_t, energy_lost)
      if (status /= OBLQ_OK) &
         call rebound_nan(v1_after, w1_after, v2_after, w2_after, p, e_t, energy_lost, a)
      if (present(alpha)) alpha = a
   end subroutine oblique_rebound_3d

   !> oblique_rebound_3d with P from a curve: gamma is the curve's (no gamma argument).
   subroutine oblique_rebound_3d_curve(curve, m1, r1, kappa1, m2, r2, kappa2, mu, &
                                       v1, w1, v2, w2, normal, v1_after, w1_after, &
                                       v2_after, w2_after, p, e_t, energy_lost, status, &
                                       clamp, alpha)
      type(oblique_curve), intent(in) :: curve
      real(c_double), intent(in) :: m1, r1, kappa1, m2, r2, kappa2, mu
      real(c_double), intent(in) :: v1(3), w1(3), v2(3), w2(3), normal(3)
      real(c_double), intent(out) :: v1_after(3), w1_after(3), v2_after(3), w2_after(3)
      real(c_double), intent(out) :: p, e_t, energy_lost
      integer(c_int), intent(out) :: status
      logical, intent(in), optional :: clamp
      real(c_double), intent(out), optional :: alpha
      real(c_double) :: a
      status = oblqf_rebound_3d_curve(curve%handle, m1, r1, kappa1, m2, r2, kappa2, mu, &
                                      v1, w1, v2, w2, normal, clamp_flag(clamp), v1_after, &
                                      w1_after, v2_after, w2_after, p, a, e_t, energy_lost)
      if (status /= OBLQ_OK) &
         call rebound_nan(v1_after, w1_after, v2_after, w2_after, p, e_t, energy_lost, a)
      if (present(alpha)) alpha = a
   end subroutine oblique_rebound_3d_curve

   !> gamma = sqrt((m*/m_t) G*/E*) of sphere 1 (m1, r1, kappa1; Young's modulus e1 in Pa,
   !> Poisson's ratio nu1) on a wall (m2 = 0; e2, nu2 the wall's) or on sphere 2 (m2, r2,
   !> kappa2; e2, nu2). A rigid body: e = +infinity (not both).
   subroutine oblique_gamma_of(m1, r1, kappa1, e1, nu1, m2, r2, kappa2, e2, nu2, gamma, status)
      real(c_double), intent(in) :: m1, r1, kappa1, e1, nu1, m2, r2, kappa2, e2, nu2
      real(c_double), intent(out) :: gamma
      integer(c_int), intent(out) :: status
      status = oblqf_gamma_of(m1, r1, kappa1, m2, r2, kappa2, e1, nu1, e2, nu2, gamma)
      if (status /= OBLQ_OK) gamma = nan()
   end subroutine oblique_gamma_of

   !> The text of a status code: what went wrong, the argument and its allowed range.
   function oblique_message(status) result(msg)
      integer(c_int), intent(in) :: status
      character(len=:), allocatable :: msg
      character(kind=c_char) :: none(1)
      integer(c_int) :: n
      n = oblqf_message(status, none, 0_c_int)
      allocate (character(len=n) :: msg)
      if (n > 0) n = oblqf_message(status, msg, n)
   end function oblique_message

end module oblique_eval
