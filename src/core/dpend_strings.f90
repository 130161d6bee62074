!> Small text helpers for messages and reports: numbers as text (`real_str`, the one
!> formatter of reals for people; `to_str` of integers; `seconds_str`), lower case,
!> padding, and `printable` (the one escaping helper of dpend_parse: control bytes as
!> \t, \n, \xNN, so that a message stays one line), and the names a user may mistype
!> (`nearest_name`, `did_you_mean`: the closest of a list by edit distance, only when
!> close; `canonical_name`: a name of a list whatever its case). Pure, no state.
module dpend_strings
   use dpend_kinds, only: dp, i8
   use dpend_parse, only: int_text, printable => escaped
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan, ieee_is_negative
   implicit none
   private
   public :: to_lower, printable, pad, real_str, seconds_str, to_str, with_uncertainty, &
      distance_in_errors, interval_text, word_wrap, replace_char
   public :: edit_distance, nearest_name, did_you_mean, canonical_name

   !> Text of an integer (default or 64-bit), without blanks.
   interface to_str
      module procedure int_str
      procedure int_text   ! 64-bit: dpend_parse's
   end interface to_str

contains

   !> `s` with ASCII capitals in lower case.
   pure function to_lower(s) result(t)
      character(len=*), intent(in) :: s  !! text
      character(len=len(s)) :: t
      integer :: i
      t = s
      do i = 1, len(s)
         if (s(i:i) >= 'A' .and. s(i:i) <= 'Z') t(i:i) = achar(iachar(s(i:i)) + 32)
      end do
   end function to_lower

   !> `text` without trailing blanks, padded with blanks to `width` columns (at least
   !> one blank).
   pure function pad(text, width) result(t)
      character(len=*), intent(in) :: text  !! text
      integer, intent(in) :: width          !! columns
      character(len=:), allocatable :: t
      t = trim(text)//repeat(' ', max(1, width - len_trim(text)))
   end function pad

   !> The one formatter of real numbers for people: the shortest text that reads
   !> back to the same bits (or, with `digits`, rounded to at most that many
   !> significant digits, for measured or derived values). Plain decimals for
   !> 1e-4 <= |x| < 1e6 and for integers up to 1e15 whose plain form is not longer,
   !> else 'd.ddde-12' style: 0.001, 9.8, 20, 1234567, 1e-12, 2.5e6, -2.5e300,
   !> 5e-324, 0.3333333333333333; '0', '-0', 'NaN', 'Infinity', '-Infinity'.
   pure function real_str(x, digits) result(s)
      real(dp), intent(in) :: x                 !! the number
      integer, intent(in), optional :: digits   !! most significant digits (1 to 17)
      character(len=:), allocatable :: s
      character(len=40) :: buf
      character(len=:), allocatable :: mant, plain, expo
      integer :: p, p_max, e, stat, k
      real(dp) :: y
      if (ieee_is_nan(x)) then
         s = 'NaN'
         return
      else if (.not. ieee_is_finite(x)) then
         s = merge('Infinity ', '-Infinity', x > 0.0_dp)
         s = trim(s)
         return
      else if (x == 0.0_dp) then
         s = merge('-0', '0 ', ieee_is_negative(x))
         s = trim(s)
         return
      end if
      p_max = 17
      if (present(digits)) p_max = max(1, min(17, digits))
      do p = 1, p_max
         write (buf, '(es'//int_str(p + 9)//'.'//int_str(p - 1)//'e4)') abs(x)
         if (above_huge(buf)) cycle   ! reading it would overflow
         read (buf, *, iostat=stat) y
         if (stat == 0 .and. y == abs(x)) exit
      end do
      p = min(p, p_max)
      write (buf, '(es'//int_str(p + 9)//'.'//int_str(p - 1)//'e4)') abs(x)
      buf = adjustl(buf)
      k = index(buf, 'E')
      read (buf(k + 1:), *) e
      ! the significant digits without the point and trailing zeros: x = d.ddd 10^e
      mant = buf(1:1)//buf(3:k - 1)
      do while (len(mant) > 1 .and. mant(len(mant):len(mant)) == '0')
         mant = mant(:len(mant) - 1)
      end do
      expo = mant(1:1)
      if (len(mant) > 1) expo = expo//'.'//mant(2:)
      expo = expo//'e'//int_str(e)
      if (e >= -4 .and. e < 6) then
         s = decimal(mant, e)
      else if (e >= 6 .and. e < 15 .and. len(mant) <= e + 1) then
         plain = decimal(mant, e)
         s = expo
         if (len(plain) <= len(expo)) s = plain
      else
         s = expo
      end if
      if (x < 0.0_dp) s = '-'//s
   contains
      !> Whether the text 'd.dddE+eeee' of a positive number exceeds huge(1.0_dp).
      pure logical function above_huge(t)
         character(len=*), intent(in) :: t
         real(dp) :: m
         integer :: k, ee, stat
         above_huge = .false.
         k = index(t, 'E')
         read (t(k + 1:), *, iostat=stat) ee
         if (stat /= 0 .or. ee < 308) return
         read (t(:k - 1), *, iostat=stat) m
         above_huge = ee > 308 .or. m > 1.7976931348623157_dp
      end function above_huge

      !> Plain decimal text of the digits `m` times 10^(e - len(m) + 1).
      pure function decimal(m, e) result(t)
         character(len=*), intent(in) :: m
         integer, intent(in) :: e
         character(len=:), allocatable :: t
         if (e < 0) then
            t = '0.'//repeat('0', -e - 1)//m
         else if (len(m) <= e + 1) then
            t = m//repeat('0', e + 1 - len(m))
         else
            t = m(:e + 1)//'.'//m(e + 2:)
         end if
      end function decimal
   end function real_str

   !> An estimate with its uncertainty, each to the digits the uncertainty supports:
   !> u rounded to two significant digits and x to the same decimal place, 'x +- u'
   !> (0.824 +- 0.093, 1.1540 +- 0.0016, 123500 +- 2300); with more than 6 decimals or
   !> beyond 1e7 a common exponent, '(8.200 +- 0.031)e-07'. Without a usable uncertainty (0, negative or
   !> not finite) x alone to 6 digits and ' (no uncertainty)'; x not finite as it is.
   function with_uncertainty(x, u) result(s)
      real(dp), intent(in) :: x   !! the estimate
      real(dp), intent(in) :: u   !! its uncertainty (a standard error), same unit
      character(len=:), allocatable :: s
      real(dp) :: scale
      integer :: d, e
      if (.not. ieee_is_finite(x)) then
         s = real_str(x)
         return
      end if
      if (.not. usable(u)) then
         s = real_str(x, 6)//' (no uncertainty)'
         return
      end if
      call decimal_place(max(abs(x), u), u, d, e)
      if (e == 0) then
         s = fixed(x, d)//' +- '//fixed(u, d)
      else
         scale = 10.0_dp**real(e, dp)
         s = '('//fixed(x/scale, d)//' +- '//fixed(u/scale, d)//')'//exponent_text(e)
      end if
   end function with_uncertainty

   !> An interval [a, b] of an estimate with uncertainty u, its ends to the decimal
   !> place `with_uncertainty` gives the estimate: '[0.2262, 0.2323]', or with a
   !> common exponent '[8.140, 8.260]e-07'; without a usable u, each to 6 digits.
   function interval_text(a, b, u) result(s)
      real(dp), intent(in) :: a, b   !! the ends
      real(dp), intent(in) :: u      !! the estimate's uncertainty, same unit
      character(len=:), allocatable :: s
      real(dp) :: scale
      integer :: d, e
      if (.not. (ieee_is_finite(a) .and. ieee_is_finite(b) .and. usable(u))) then
         s = '['//real_str(a, 6)//', '//real_str(b, 6)//']'
         return
      end if
      call decimal_place(max(abs(a), abs(b), u), u, d, e)
      scale = 10.0_dp**real(e, dp)
      s = '['//fixed(a/scale, d)//', '//fixed(b/scale, d)//']'
      if (e /= 0) s = s//exponent_text(e)
   end function interval_text

   !> Whether u is an uncertainty to round to: finite and > 0 (two tests: Fortran's
   !> .and. may evaluate both, and u > 0 with a NaN traps).
   pure logical function usable(u)
      real(dp), intent(in) :: u
      usable = ieee_is_finite(u)
      if (usable) usable = u > 0.0_dp
   end function usable

   !> The decimals d that keep two significant digits of u > 0 and, for numbers up to
   !> `big` beyond 1e7 or with more than 6 decimals, the common exponent e (then d
   !> counts the decimals of the numbers divided by 10^e; else e = 0).
   pure subroutine decimal_place(big, u, d, e)
      real(dp), intent(in) :: big, u
      integer, intent(out) :: d, e
      real(dp) :: ur
      d = 1 - floor(log10(u))                 ! decimals that keep two digits of u
      ur = anint(10.0_dp*u/10.0_dp**real(floor(log10(u)), dp))   ! its two digits, 10 .. 100
      if (ur >= 100.0_dp) d = d - 1           ! 0.0996 rounds to 0.10: one decimal less
      e = 0
      if (big < 1e7_dp .and. d <= 6) return
      e = floor(log10(big))
      d = min(d + e, 16)   ! a double's digits at most
   end subroutine decimal_place

   !> 'e-07', 'e+08': a common exponent.
   pure function exponent_text(e) result(t)
      integer, intent(in) :: e
      character(len=:), allocatable :: t
      character(len=8) :: buf
      write (buf, '(i2.2)') abs(e)
      t = 'e'//merge('-', '+', e < 0)//trim(buf)
   end function exponent_text

   !> y rounded to `dec` decimals (dec < 0: to 10^-dec), without exponent.
   function fixed(y, dec) result(t)
      real(dp), intent(in) :: y
      integer, intent(in) :: dec
      character(len=:), allocatable :: t
      character(len=48) :: buf
      if (dec <= 0) then
         write (buf, '(i0)') nint(anint(y*10.0_dp**real(dec, dp))/10.0_dp**real(dec, dp), i8)
      else
         write (buf, '(f0.'//int_str(dec)//')') anint(y*10.0_dp**real(dec, dp))/ &
            10.0_dp**real(dec, dp)
      end if
      t = trim(buf)
      if (t(1:1) == '.') t = '0'//t
      if (len(t) >= 2) then
         if (t(1:2) == '-.') t = '-0'//t(2:)
      end if
      if (t(1:1) == '-' .and. verify(t, '-0.') == 0) t = t(2:)   ! no -0.00
   end function fixed

   !> `text` with every character `old` replaced by `new` ('t_end' to 't-end').
   pure function replace_char(text, old, new) result(t)
      character(len=*), intent(in) :: text  !! the text
      character(len=1), intent(in) :: old   !! the character replaced
      character(len=1), intent(in) :: new   !! its replacement
      character(len=len(text)) :: t
      integer :: i
      t = text
      do i = 1, len(t)
         if (t(i:i) == old) t(i:i) = new
      end do
   end function replace_char

   !> `text` broken at blanks into lines of at most `width` characters (a longer word
   !> on a line of its own), every line after the first starting with `indent`
   !> blanks; the lines joined by new_line.
   pure function word_wrap(text, width, indent) result(s)
      character(len=*), intent(in) :: text   !! one paragraph
      integer, intent(in) :: width           !! longest line, indent included
      integer, intent(in) :: indent          !! blanks before the second line on
      character(len=:), allocatable :: s
      character(len=:), allocatable :: line
      integer :: i, j, n
      logical :: fresh   ! no word on the line yet
      s = ''
      line = ''
      fresh = .true.
      i = 1
      n = len_trim(text)
      do while (i <= n)
         if (text(i:i) == ' ') then
            i = i + 1
            cycle
         end if
         j = index(text(i:n), ' ')
         if (j == 0) then
            j = n
         else
            j = i + j - 2
         end if
         if (fresh) then
            line = line//text(i:j)
         else if (len(line) + 1 + (j - i + 1) > width) then
            s = s//line//new_line('a')
            line = repeat(' ', indent)//text(i:j)
         else
            line = line//' '//text(i:j)
         end if
         fresh = .false.
         i = j + 1
      end do
      s = s//line
   end function word_wrap

   !> How far an estimate x lies from a value in standard errors u: '0 within 1
   !> standard error', '1 within 2 standard errors', '0 is 3.4 standard errors away'
   !> (`value_text` names the value); 'no standard error' for u not > 0 or NaN.
   function distance_in_errors(x, value, value_text, u) result(s)
      real(dp), intent(in) :: x, value, u      !! the estimate, the value, the error
      character(len=*), intent(in) :: value_text  !! the value as printed, e.g. '0'
      character(len=:), allocatable :: s
      real(dp) :: d
      s = 'no standard error'
      if (ieee_is_nan(x) .or. ieee_is_nan(u)) return   ! (an ordered test with NaN traps)
      if (.not. (u > 0.0_dp)) return
      d = abs(x - value)
      if (d <= u) then
         s = value_text//' within 1 standard error'
      else if (d <= 2*u) then
         s = value_text//' within 2 standard errors'
      else
         s = value_text//' is '//real_str(d/u, 2)//' standard errors away'
      end if
   end function distance_in_errors

   !> A duration for people, from `real_str`: two significant digits below 1 s
   !> (0.4, 0.043), one decimal above (2.5, 12.3, 1234.5); never '.4'.
   pure function seconds_str(t) result(s)
      real(dp), intent(in) :: t  !! seconds
      character(len=:), allocatable :: s
      if (.not. ieee_is_finite(t)) then
         s = real_str(t)
      else if (abs(t) < 1.0_dp) then
         s = real_str(t, 2)
      else
         s = real_str(t, min(17, floor(log10(abs(t))) + 2))
      end if
   end function seconds_str

   pure function int_str(i) result(s)
      integer, intent(in) :: i  !! the number
      character(len=:), allocatable :: s
      s = int_text(int(i, i8))
   end function int_str

   !> The edit distance of `a` and `b` (optimal string alignment: insertions,
   !> deletions, substitutions and swaps of two neighbours count 1), comparing
   !> without case and with '_' and '-' alike (`--t_end` is `--t-end`).
   pure integer function edit_distance(a, b) result(d)
      character(len=*), intent(in) :: a  !! one word
      character(len=*), intent(in) :: b  !! the other
      character(len=len(a)) :: x
      character(len=len(b)) :: y
      integer :: t(0:len(a), 0:len(b)), i, j, cost
      x = folded(a)
      y = folded(b)
      do i = 0, len(x)
         t(i, 0) = i
      end do
      do j = 0, len(y)
         t(0, j) = j
      end do
      do i = 1, len(x)
         do j = 1, len(y)
            cost = merge(0, 1, x(i:i) == y(j:j))
            t(i, j) = min(t(i - 1, j) + 1, t(i, j - 1) + 1, t(i - 1, j - 1) + cost)
            if (i > 1 .and. j > 1) then   ! (max: indices the compiler sees in bounds)
               if (x(i:i) == y(j - 1:j - 1) .and. x(i - 1:i - 1) == y(j:j)) &
                  t(i, j) = min(t(i, j), t(max(i - 2, 0), max(j - 2, 0)) + 1)
            end if
         end do
      end do
      d = t(len(x), len(y))
   contains
      pure function folded(s) result(f)
         character(len=*), intent(in) :: s
         character(len=len(s)) :: f
         integer :: k
         f = to_lower(s)
         do k = 1, len(f)
            if (f(k:k) == '_') f(k:k) = '-'
         end do
      end function folded
   end function edit_distance

   !> The word of `words` (separated by blanks or commas) nearest to `name` by
   !> `edit_distance`, if it is close: at most 1 edit for names of up to 4
   !> characters (without leading dashes), 2 for longer ones, and fewer edits than
   !> the name has characters, and not only in its digits (theta4, rk5: another
   !> number, not a typo); '' if none is (or `name` is one of them). The first of
   !> equally near words wins.
   pure function nearest_name(name, words) result(best)
      character(len=*), intent(in) :: name   !! what the user gave
      character(len=*), intent(in) :: words  !! the accepted names
      character(len=:), allocatable :: best
      integer :: a, b, d, d_best, n_core, limit
      best = ''
      n_core = len_trim(name) - (verify(name, '-') - 1)
      if (verify(name, '-') == 0) return
      limit = merge(1, 2, n_core <= 4)
      limit = min(limit, n_core - 1)
      d_best = limit + 1
      a = 1
      do
         call next_word(words, a, b)
         if (a > len(words)) exit
         d = edit_distance(trim(name), words(a:b - 1))
         if (d == 0 .and. trim(name) == words(a:b - 1)) then
            best = ''
            return
         end if
         ! another number is no typo (theta4 for 3 links, rk5): no suggestion
         if (d > 0 .and. scan(name, '0123456789') > 0) then
            if (edit_distance(no_digits(trim(name)), no_digits(words(a:b - 1))) == 0) &
               d = d_best
         end if
         if (d < d_best) then
            d_best = d
            best = words(a:b - 1)
         end if
         a = b
      end do
   contains
      pure function no_digits(w) result(t)
         character(len=*), intent(in) :: w
         character(len=:), allocatable :: t
         integer :: k
         t = ''
         do k = 1, len(w)
            if (index('0123456789', w(k:k)) == 0) t = t//w(k:k)
         end do
      end function no_digits
   end function nearest_name

   !> The next word of `words` (separated by blanks, commas, tabs or line ends) at or
   !> after position `a`: words(a:b - 1); a > len(words) when there is none.
   pure subroutine next_word(words, a, b)
      character(len=*), intent(in) :: words  !! the list
      integer, intent(inout) :: a            !! where to look; the word's start
      integer, intent(out) :: b              !! one past the word's end
      character(len=*), parameter :: seps = ' ,'//achar(9)//achar(10)
      do while (a <= len(words))
         if (index(seps, words(a:a)) == 0) exit
         a = a + 1
      end do
      b = a
      do while (b <= len(words))
         if (index(seps, words(b:b)) > 0) exit
         b = b + 1
      end do
   end subroutine next_word

   !> 'did you mean X?' for the word X of `words` nearest to `name` (`nearest_name`),
   !> or '' when none is close. With `lead`, the text starts with it ('; ' after the
   !> parenthesis of the accepted names).
   pure function did_you_mean(name, words, lead) result(s)
      character(len=*), intent(in) :: name            !! what the user gave
      character(len=*), intent(in) :: words           !! the accepted names
      character(len=*), intent(in), optional :: lead  !! text before it
      character(len=:), allocatable :: s
      s = nearest_name(name, words)
      if (len(s) == 0) return
      s = 'did you mean '//s//'?'
      if (present(lead)) s = lead//s
   end function did_you_mean

   !> The word of `words` (separated by blanks or commas) equal to `name` without
   !> regard to case (`RK4` is `rk4`), or `name` itself if there is none.
   pure function canonical_name(name, words) result(s)
      character(len=*), intent(in) :: name   !! what the user gave
      character(len=*), intent(in) :: words  !! the accepted names
      character(len=:), allocatable :: s
      integer :: a, b
      s = name
      a = 1
      do
         call next_word(words, a, b)
         if (a > len(words)) exit
         if (to_lower(words(a:b - 1)) == to_lower(name)) then
            s = words(a:b - 1)
            return
         end if
         a = b
      end do
   end function canonical_name
end module dpend_strings
