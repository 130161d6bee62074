!> The one strict scalar parser of dpend: every number a user gives
!> (flags, comma lists, namelist files, CSV fields) is read here. The whole token
!> must be a number of the grammar
!>
!>     real:    [sign] digits [. [digits]] [exponent]  |  [sign] . digits [exponent]
!>     exponent: (e|E|d|D) [sign] digits
!>     integer: [sign] digits
!>
!> Anything else (a blank, tab, ';', newline or ',' inside, hex, 'inf', 'nan', trailing
!> junk) is refused; the reason names the first offending character, escaped
!> (`escaped`) so that the message stays one line. Trailing blanks (of fixed-length
!> buffers) are ignored; leading ones are not. A real beyond the largest double is
!> refused before it is read (reading it overflows: a trap in debug builds); Inf and
!> NaN are refused as not finite.
!>
!> This module has no dependency but the kinds, so that every layer can use it;
!> dpend_cli's `parse_real` and `parse_int` wrap it with the 'invalid FIELD: ' prefix.
module dpend_parse
   use dpend_kinds, only: dp, i8
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: read_real, read_int, escaped, quoted, overflows_real, number_end, int_text

   !> Read a default or 64-bit integer token.
   interface read_int
      module procedure read_int_default, read_int_i8
   end interface read_int

   !> Most characters of a value echoed by `quoted` (before escaping).
   integer, parameter :: max_echo = 64

contains

   !> `s` with control characters escaped so that it prints on one line: tab `\t`,
   !> line feed `\n`, carriage return `\r`, a backslash `\\`, any other byte outside
   !> printable ASCII (control bytes, DEL, bytes of UTF-8 sequences) `\xNN`. With
   !> `controls_only` only control bytes and DEL are escaped (a backslash and UTF-8
   !> stay): the last guard of a whole message, whose values are escaped already.
   pure function escaped(s, controls_only) result(t)
      character(len=*), intent(in) :: s              !! any bytes
      logical, intent(in), optional :: controls_only !! leave '\' and bytes >= 128
      character(len=:), allocatable :: t
      character(len=*), parameter :: hex_digits = '0123456789ABCDEF'
      integer :: i, c, n
      logical :: all_bytes
      all_bytes = .true.
      if (present(controls_only)) all_bytes = .not. controls_only
      n = 0
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (.not. all_bytes .and. (c == 92 .or. c > 127)) then
            n = n + 1
         else
            n = n + escaped_length(c)
         end if
      end do
      allocate (character(len=n) :: t)
      n = 0
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (.not. all_bytes .and. (c == 92 .or. c > 127)) then
            t(n + 1:n + 1) = s(i:i)
            n = n + 1
            cycle
         end if
         select case (c)
         case (9); t(n + 1:n + 2) = '\t'
         case (10); t(n + 1:n + 2) = '\n'
         case (13); t(n + 1:n + 2) = '\r'
         case (92); t(n + 1:n + 2) = '\\'
         case (32:91, 93:126); t(n + 1:n + 1) = s(i:i)
         case default
            t(n + 1:n + 4) = '\x'//hex_digits(c/16 + 1:c/16 + 1)// &
                             hex_digits(mod(c, 16) + 1:mod(c, 16) + 1)
         end select
         n = n + escaped_length(c)
      end do
   contains
      pure integer function escaped_length(code)
         integer, intent(in) :: code
         select case (code)
         case (9, 10, 13, 92); escaped_length = 2
         case (32:91, 93:126); escaped_length = 1
         case default; escaped_length = 4
         end select
      end function escaped_length
   end function escaped

   !> `s` in single quotes, escaped, at most max_echo characters of it (then '...').
   pure function quoted(s) result(t)
      character(len=*), intent(in) :: s  !! a value as given
      character(len=:), allocatable :: t
      if (len(s) > max_echo) then
         t = "'"//escaped(s(:max_echo))//"...'"
      else
         t = "'"//escaped(s)//"'"
      end if
   end function quoted

   !> Position of the first character of `s` that does not continue a number of the
   !> grammar (integer: `integer` true), len(s) + 1 when the whole of `s` is one, and
   !> also len(s) + 1 for an incomplete number ('', '-', '1e', '.'): `complete` tells.
   pure subroutine number_end(s, integer, pos, complete)
      character(len=*), intent(in) :: s   !! the token (no trailing blanks)
      logical, intent(in) :: integer      !! only [sign] digits
      integer, intent(out) :: pos         !! first offending position
      logical, intent(out) :: complete    !! the grammar is satisfied up to pos - 1
      integer :: n_mant
      logical :: digits_seen
      pos = 1
      complete = .false.
      if (pos <= len(s)) then
         if (s(pos:pos) == '+' .or. s(pos:pos) == '-') pos = pos + 1
      end if
      call skip_digits(s, pos, n_mant)
      digits_seen = n_mant > 0
      if (.not. integer .and. pos <= len(s)) then
         if (s(pos:pos) == '.') then
            pos = pos + 1
            call skip_digits(s, pos, n_mant)
            digits_seen = digits_seen .or. n_mant > 0
         end if
      end if
      if (.not. digits_seen) return
      complete = .true.
      if (integer .or. pos > len(s)) return
      if (index('eEdD', s(pos:pos)) == 0) return
      complete = .false.
      pos = pos + 1
      if (pos <= len(s)) then
         if (s(pos:pos) == '+' .or. s(pos:pos) == '-') pos = pos + 1
      end if
      call skip_digits(s, pos, n_mant)
      complete = n_mant > 0
   contains
      pure subroutine skip_digits(str, p, count)
         character(len=*), intent(in) :: str
         integer, intent(inout) :: p
         integer, intent(out) :: count
         count = 0
         do while (p <= len(str))
            if (str(p:p) < '0' .or. str(p:p) > '9') exit
            p = p + 1
            count = count + 1
         end do
      end subroutine skip_digits
   end subroutine number_end

   !> Why `text` is not a number of the grammar ('' when it is one): the offending
   !> character and its position, or that the number is incomplete or empty.
   pure function syntax_problem(text, integer) result(why)
      character(len=*), intent(in) :: text  !! the token
      logical, intent(in) :: integer        !! integer grammar
      character(len=:), allocatable :: why
      character(len=:), allocatable :: what, expected
      integer :: pos
      logical :: complete
      why = ''
      what = 'a number'
      expected = '[sign] digits [.digits] [e[sign]digits]'
      if (integer) then
         what = 'an integer'
         expected = '[sign] digits'
      end if
      if (len(text) == 0) then
         why = 'is not '//what//' (empty)'
         return
      end if
      call number_end(text, integer, pos, complete)
      if (pos <= len(text)) then
         why = 'is not '//what//' (character '//quoted(text(pos:pos))//' at position '// &
               int_text(int(pos, i8))//'; expected '//expected//')'
      else if (.not. complete) then
         why = 'is not '//what//' (incomplete; expected '//expected//')'
      end if
   end function syntax_problem

   !> Whether `t` (no trailing blanks) spells Inf, Infinity or NaN, any case, signed.
   pure logical function non_finite_word(t)
      character(len=*), intent(in) :: t  !! the token
      character(len=:), allocatable :: u
      integer :: i
      u = t
      if (len(u) > 0) then
         if (u(1:1) == '+' .or. u(1:1) == '-') u = u(2:)
      end if
      do i = 1, len(u)
         if (u(i:i) >= 'A' .and. u(i:i) <= 'Z') u(i:i) = achar(iachar(u(i:i)) + 32)
      end do
      non_finite_word = u == 'inf' .or. u == 'infinity' .or. u == 'nan'
   end function non_finite_word

   !> Read the real number `text` (trailing blanks ignored). `why` is '' when it is
   !> a finite number of the grammar within ±huge, else the reason, a phrase that
   !> follows the quoted value: "is not a number (character ';' at position 2; ...)",
   !> "is not finite (a finite number is required)", "is beyond the largest double
   !> (1.797e308)". x is 0 when refused.
   subroutine read_real(text, x, why)
      character(len=*), intent(in) :: text                !! the token
      real(dp), intent(out) :: x                          !! its value
      character(len=:), allocatable, intent(out) :: why   !! '' or the reason
      integer :: stat, n
      x = 0.0_dp
      n = len_trim(text)
      if (non_finite_word(text(:n))) then
         why = 'is not finite (a finite number is required)'
         return
      end if
      why = syntax_problem(text(:n), .false.)
      if (len(why) > 0) return
      if (overflows_real(text(:n))) then   ! reading it would overflow (debug: a trap)
         why = 'is beyond the largest double (1.797e308)'
         return
      end if
      read (text(:n), *, iostat=stat) x
      if (stat /= 0) then
         x = 0.0_dp
         why = 'is not a number'
      else if (.not. ieee_is_finite(x)) then
         x = 0.0_dp
         why = 'is not finite (a finite number is required)'
      end if
   end subroutine read_real

   !> Read the 64-bit integer `text` (trailing blanks ignored); `why` as `read_real`
   !> ("is not an integer (...)", "is beyond the integer range [-9.2e18, 9.2e18]").
   subroutine read_int_i8(text, n, why)
      character(len=*), intent(in) :: text                !! the token
      integer(i8), intent(out) :: n                       !! its value
      character(len=:), allocatable, intent(out) :: why   !! '' or the reason
      call read_int_range(text, -huge(n), huge(n), n, why)
   end subroutine read_int_i8

   !> Read the default integer `text`; `why` as `read_int_i8`.
   subroutine read_int_default(text, n, why)
      character(len=*), intent(in) :: text                !! the token
      integer, intent(out) :: n                           !! its value
      character(len=:), allocatable, intent(out) :: why   !! '' or the reason
      integer(i8) :: n8
      call read_int_range(text, int(-huge(n), i8), int(huge(n), i8), n8, why)
      n = int(n8)
   end subroutine read_int_default

   !> An integer token within [lo, hi] (both within ±huge(1_i8)).
   subroutine read_int_range(text, lo, hi, n, why)
      character(len=*), intent(in) :: text
      integer(i8), intent(in) :: lo, hi
      integer(i8), intent(out) :: n
      character(len=:), allocatable, intent(out) :: why
      integer :: k, first, stat
      n = 0
      k = len_trim(text)
      why = syntax_problem(text(:k), .true.)
      if (len(why) > 0) return
      first = 1
      if (text(1:1) == '+' .or. text(1:1) == '-') first = 2
      do while (first < k .and. text(first:first) == '0')   ! leading zeros
         first = first + 1
      end do
      stat = 0
      if (k - first + 1 <= 19) then   ! beyond 19 digits: beyond huge(1_i8); the read
                                      ! refuses 19 digits above it (iostat, no trap)
         read (text(first:k), *, iostat=stat) n
         if (text(1:1) == '-') n = -n
      end if
      if (k - first + 1 > 19 .or. stat /= 0 .or. n < lo .or. n > hi) then
         n = 0
         why = 'is beyond the integer range ['//int_text(lo)//', '//int_text(hi)//']'
      end if
   end subroutine read_int_range

   !> Whether the decimal text of a real number ([sign] digits [. digits] [e|d [sign]
   !> digits]) is beyond huge(1.0_dp) in magnitude: reading it would overflow, which
   !> glibc's strtod signals as an IEEE overflow (a trap under -ffpe-trap=overflow)
   !> before the value can be checked. Text of another form gives .false. (the read
   !> itself then refuses it, or it is Inf/NaN, checked after the read).
   pure logical function overflows_real(text)
      character(len=*), intent(in) :: text  !! the number's text
      character(len=:), allocatable :: t, mant, digits
      real(dp) :: lead
      integer :: k, i, e, point, first, n_int, stat, e_sign
      overflows_real = .false.
      t = trim(adjustl(text))
      if (len(t) == 0) return
      if (t(1:1) == '+' .or. t(1:1) == '-') t = t(2:)
      k = scan(t, 'eEdD')
      mant = t
      e = 0
      if (k > 0) then
         mant = t(:k - 1)
         i = k + 1
         e_sign = 1
         if (i <= len(t)) then
            if (t(i:i) == '+' .or. t(i:i) == '-') then
               if (t(i:i) == '-') e_sign = -1
               i = i + 1
            end if
         end if
         if (i > len(t)) return
         if (verify(t(i:), '0123456789') /= 0) return
         do while (i < len(t) .and. t(i:i) == '0')   ! leading zeros of the exponent
            i = i + 1
         end do
         if (len(t) - i + 1 > 6) then       ! |exponent| >= 10^6
            overflows_real = e_sign > 0 .and. verify(mant, '0.') /= 0
            return
         end if
         read (t(i:), *, iostat=stat) e
         if (stat /= 0) return
         e = e_sign*e
      end if
      if (len(mant) == 0 .or. verify(mant, '0123456789.') /= 0) return
      point = index(mant, '.')
      if (point > 0 .and. index(mant(point + 1:), '.') > 0) return
      if (point == 0) point = len(mant) + 1
      digits = mant(:point - 1)//mant(min(point + 1, len(mant) + 1):)
      n_int = point - 1
      first = verify(digits, '0')
      if (first == 0) return                 ! zero
      ! x = 0.d_first d_(first+1) ... 10^(n_int - first + 1 + e): the leading digit's
      ! decimal exponent is n_int - first + e
      if (n_int - first + e < 308) return
      if (n_int - first + e > 308) then
         overflows_real = .true.
         return
      end if
      ! exponent 308: compare the leading digits with 1.7976931348623157
      t = digits(first:first)//'.'//digits(first + 1:min(len(digits), first + 17))//'0'
      read (t, *, iostat=stat) lead
      overflows_real = stat == 0 .and. lead > 1.7976931348623157_dp
   end function overflows_real

   !> Decimal text of an integer.
   pure function int_text(i) result(s)
      integer(i8), intent(in) :: i  !! the number
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function int_text
end module dpend_parse
