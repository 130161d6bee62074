!> The sweep's resume (docs/sweep.md, "Output, crash safety and resume"): opening or
!> creating the working file, refusing another configuration, and verifying the
!> blocks an earlier run flagged done before they are trusted.
!>
!> Crash safety and resume. While it runs, the results go to a *working* file,
!> FILE.part beside the output FILE, whose datasets are chunked (one chunk per
!> block), unfiltered and allocated in full when the file is created (not written:
!> its disk space is reserved), so writing a block changes raw data only, never the
!> file's metadata: a kill at any moment leaves a valid file. A block's data and
!> their CRC-32 are written and flushed before its flag in /sweep/done. A kill
!> during a block's write may tear its chunks (a checksum that no longer matches);
!> the block is not flagged, so the resume does not check its checksums
!> (`verify_blocks`) nor needs its old contents (`write_block`).
!> When every block is done, the results are rewritten with compressed chunks
!> through the one writer (dpend_output: temporary file, checked close, one-step
!> move) into FILE, marked complete, and the working file is removed. FILE itself
!> is never changed before the new result is complete. Rerunning the same command
!> computes only the blocks not flagged done in FILE.part; another configuration
!> is refused unless --force.
module dpend_sweep_resume
   use dpend_kinds, only: dp, i8
   use dpend_error, only: error_t, fatal_error, run_failure
   use dpend_output, only: output_t, check_output_path
   use dpend_os, only: path_kind, path_file
   use dpend_hdf5, only: h5file_t, is_hdf5
   use dpend_cli, only: to_str, real_str
   use dpend_progress, only: show_progress_header
   use dpend_sweep_compare, only: config_value
   use dpend_sweep_setup, only: sweep_setup_t, block_range
   use dpend_sweep_layout, only: result_names, create_layout, write_block, working_file, &
      install_file, crc_path, read_crcs
   use dpend_checksum, only: crc32_of
   implicit none
   private
   public :: open_output

contains

   !> Open the working file for writing: resume FILE.part of the same configuration,
   !> refuse another unless --force, else create a new working file. A complete FILE
   !> of the same configuration needs nothing (`complete` = 1); another FILE is
   !> refused unless --force, and with --force it is replaced only at the end.
   subroutine open_output(setup, h5, done, complete, error)
      type(sweep_setup_t), intent(in) :: setup          !! setup
      type(h5file_t), intent(inout) :: h5               !! the working file, opened 'rw'
      integer, allocatable, intent(out) :: done(:)      !! block flags
      integer, intent(out) :: complete                  !! 1 if already complete
      type(error_t), allocatable, intent(out) :: error  !! refused or I/O failure
      type(output_t) :: probe, work
      character(len=:), allocatable :: file, part
      logical :: force
      file = setup%cfg%run%output
      part = working_file(file)
      force = setup%cfg%run%force
      complete = 0
      ! the output and the working file: regular files or missing, in a writable
      ! directory (a real temporary file, removed at once)
      call check_output_path(file, .true., error)
      if (.not. allocated(error)) call check_output_path(part, .true., error, &
                                                          '--output (its working file)')
      if (.not. allocated(error)) call probe%begin(file, .true., error)
      call probe%discard()
      if (allocated(error)) return
      if (path_kind(file) == path_file .and. .not. force) then
         call read_stored(file, done, complete, error)
         if (allocated(error)) return
         if (complete /= 1) then
            call fatal_error(error, "invalid --output: '"//file//"' holds an unfinished "// &
                             'sweep written by an older dpend (use --force to start again)')
         end if
         return
      end if
      if (path_kind(part) == path_file .and. .not. force) then
         call read_stored(part, done, complete, error)
         if (allocated(error)) return
         call h5%open(part, 'rw', error)
         if (allocated(error)) then
            error%message = error%message//' (use --force to start again)'
            call run_failure(error)
         end if
         if (.not. allocated(error) .and. .not. setup%checksum) call check_unfiltered()
         return
      end if
      ! a new working file, complete before it gets its name
      call work%begin(part, .true., error, '--output (its working file)')
      if (allocated(error)) return
      ! nothing is refused from here on, and the layout may take long (a 10^4 x 10^4
      ! map's is 10 GB): the horizon line goes out now
      call show_progress_header()
      call create_layout(h5, work%temp, setup, .false., error)
      call install_file(h5, work, setup, error, reserve=.true.)
      if (allocated(error)) then
         error%message = 'cannot create the working file: '//error%message
         call run_failure(error)
         return
      end if
      call h5%open(part, 'rw', error)
      allocate (done(setup%nblocks))
      done = 0
   contains
      !> A program that writes blocks without checksums (the MPI sweep) cannot resume
      !> a working file that has them (one started by `dpend sweep`: CRC-32 of its
      !> blocks, or in older files HDF5's Fletcher-32 filter).
      subroutine check_unfiltered()
         character(len=32), allocatable :: reals(:), ints(:)
         integer :: n
         call result_names(setup, reals, ints)
         call h5%filters('/sweep/'//trim(reals(1)), n, error)
         if (allocated(error)) return
         if (n == 0 .and. .not. h5%exists(crc_path)) return
         call h5%close()
         call fatal_error(error, "invalid --output: '"//part//"' was started by dpend "// &
                          'sweep, whose checksummed blocks parallel HDF5 cannot write one '// &
                          'by one: finish it with dpend sweep, or use --force to start again')
      end subroutine check_unfiltered
      !> The block flags and the completeness of an existing sweep file of this
      !> configuration; refused when it is another file or another configuration.
      subroutine read_stored(path, done, complete, error)
         character(len=*), intent(in) :: path
         integer, allocatable, intent(out) :: done(:)
         integer, intent(out) :: complete
         type(error_t), allocatable, intent(out) :: error
         type(h5file_t) :: f
         character(len=:), allocatable :: stored
         complete = 0
         if (.not. is_hdf5(path)) then
            call fatal_error(error, "invalid --output: '"//path//"' exists and is not "// &
                             'an HDF5 file (use --force to overwrite)')
            return
         end if
         call f%open(path, 'r', error)
         if (.not. allocated(error)) call f%readattr('/sweep', 'config', stored, error)
         if (allocated(error)) then
            call f%close()
            call fatal_error(error, "invalid --output: '"//path//"' exists and is not "// &
                             'a dpend sweep file (use --force to overwrite)')
            return
         end if
         if (stored /= setup%config) then
            call f%close()
            call fatal_error(error, "invalid --output: '"//path//"' holds a sweep with "// &
                             'another configuration ('//first_difference(setup%config, &
                             stored)//'); use --force to overwrite it')
            return
         end if
         call f%read('/sweep/done', done, error)
         if (.not. allocated(error)) call f%readattr('/sweep', 'complete', complete, error)
         if (allocated(error)) then
            error%message = "invalid --output: '"//path//"' is damaged ("//error%message// &
                            '); use --force to start again'
         else if (size(done) /= setup%nblocks) then
            call fatal_error(error, "invalid --output: '"//path//"' has a damaged block "// &
                             'list (use --force to start again)')
         else
            call verify_blocks(f, path, setup, done, error)
         end if
         call f%close()
      end subroutine read_stored
   end subroutine open_output

   !> Check the results of an existing sweep file before it is resumed or reported
   !> complete: every flag in /sweep/done is 0 or 1; every result dataset has the
   !> sweep's shape; every block flagged done reads back as written (its CRC-32 in
   !> a working file's `crc_path`, the Fletcher-32 checksums of the chunks of a final
   !> file or an older working file; files written before checksums are read all
   !> the same) and has a status for each of its initial conditions; the chunk
   !> index of every other block reads. Those other blocks' checksums are not
   !> checked: a kill during a block's write may leave its chunks torn, and resuming
   !> rewrites them whole (`write_block`). Of a working file with CRC-32s the blocks
   !> not done are not read at all (the work of a resume is that of the blocks
   !> done): each dataset's chunk index is read once, whole, and must hold one chunk
   !> per block. A damaged file is refused, never finished or copied.
   subroutine verify_blocks(h5, path, setup, done, error)
      type(h5file_t), intent(inout) :: h5               !! the open file
      character(len=*), intent(in) :: path              !! its name, for messages
      type(sweep_setup_t), intent(in) :: setup          !! setup
      integer, intent(in) :: done(:)                    !! its block flags
      type(error_t), allocatable, intent(out) :: error  !! the first damage found
      character(len=32), allocatable :: reals(:), ints(:), names(:)
      integer, allocatable :: status(:), start(:), cnt(:), dims(:), want(:), stored(:, :)
      character(len=:), allocatable :: damaged, name
      integer :: k, b, j0, nb
      logical :: summed
      damaged = "invalid --output: '"//path//"' is damaged ("
      if (any(done /= 0 .and. done /= 1)) then
         call fatal_error(error, damaged//'/sweep/done holds flags other than 0 and 1); '// &
                          'use --force to start again')
         return
      end if
      call result_names(setup, reals, ints)   ! ints(1) is the status
      if (setup%grid) then
         want = [setup%cfg%n1, setup%cfg%n2]
      else
         want = [setup%n]
      end if
      names = [reals, ints]
      summed = h5%exists(crc_path)
      if (summed) then
         call read_crcs(h5, setup, size(names), stored, error)
         if (allocated(error)) then
            error%message = damaged//error%message//'); use --force to start again'
            return
         end if
      end if
      do k = 1, size(names)
         name = '/sweep/'//trim(names(k))
         call h5%shape(name, dims, error)
         if (allocated(error)) then
            error%message = damaged//error%message//'); use --force to start again'
            return
         end if
         if (size(dims) /= size(want)) then
            call fatal_error(error, damaged//name//' has rank '//to_str(size(dims))// &
                             ', not '//to_str(size(want))//'); use --force to start again')
         else if (any(dims /= want)) then
            call fatal_error(error, damaged//name//' has shape '//shape_str(dims)// &
                             ', not '//shape_str(want)//'); use --force to start again')
         end if
         if (allocated(error)) return
         ! a working file with CRC-32s: its chunks, one per block, were all allocated
         ! when it was made; their index is read once here, not block by block
         if (summed) call check_chunk_index(name)
         if (allocated(error)) return
      end do
      do b = 1, setup%nblocks
         if (summed .and. done(b) /= 1) cycle
         call block_range(setup, b, j0, nb)
         if (setup%grid) then
            start = [1, (j0 - 1)/setup%cfg%n1 + 1]
            cnt = [setup%cfg%n1, nb/setup%cfg%n1]
         else
            start = [j0]
            cnt = [nb]
         end if
         do k = 1, size(ints)
            call read_block(trim(ints(k)), .false., size(reals) + k)
            if (allocated(error)) return
            if (k == 1 .and. done(b) == 1 .and. any(status == 0)) then
               call fatal_error(error, damaged//'block '//to_str(b)//' is flagged done '// &
                                'but not written); use --force to start again')
               return
            end if
         end do
         do k = 1, size(reals)
            call read_block(trim(reals(k)), .true., k)
            if (allocated(error)) return
         end do
      end do
   contains
      !> The chunk index of dataset `name` reads and holds one chunk per block.
      subroutine check_chunk_index(name)
         character(len=*), intent(in) :: name
         integer(i8) :: n
         call h5%chunks(name, n, error)
         if (allocated(error)) then
            error%message = damaged//error%message//'); use --force to start again'
         else if (n /= int(setup%nblocks, i8)) then
            call fatal_error(error, damaged//name//' has '//to_str(n)//' chunks, not '// &
                             to_str(setup%nblocks)//'); use --force to start again')
         end if
      end subroutine check_chunk_index
      !> Read block b of dataset /sweep/name (integers into `status`), the k-th
      !> result, with its checksums checked if the block is flagged done: its
      !> CRC-32 in `crc_path`, or in older working files HDF5's Fletcher-32.
      subroutine read_block(name, real_values, k)
         character(len=*), intent(in) :: name
         logical, intent(in) :: real_values
         integer, intent(in) :: k
         real(dp), allocatable :: r1(:), r2(:, :)
         integer, allocatable :: i2(:, :)
         logical :: sums
         integer :: crc
         sums = done(b) == 1
         if (real_values .and. setup%grid) then
            call h5%read_slab('/sweep/'//name, start, cnt, r2, error, sums)
            if (.not. allocated(error)) crc = crc32_of(r2)
         else if (real_values) then
            call h5%read_slab('/sweep/'//name, start, cnt, r1, error, sums)
            if (.not. allocated(error)) crc = crc32_of(r1)
         else if (setup%grid) then
            call h5%read_slab('/sweep/'//name, start, cnt, i2, error, sums)
            if (.not. allocated(error)) status = reshape(i2, [size(i2)])
            if (.not. allocated(error)) crc = crc32_of(i2)
         else
            call h5%read_slab('/sweep/'//name, start, cnt, status, error, sums)
            if (.not. allocated(error)) crc = crc32_of(status)
         end if
         if (.not. allocated(error) .and. sums .and. summed) then
            if (crc /= stored(k, b)) call fatal_error(error, 'CRC-32')
         end if
         if (.not. allocated(error)) return
         if (sums) then
            error%message = damaged//'/sweep/'//name//' does not read back in block '// &
                            to_str(b)//': a checksum does not match or its chunk index '// &
                            'is broken); use --force to start again'
         else
            error%message = damaged//'/sweep/'//name//' does not read back in block '// &
                            to_str(b)//', not yet computed: its chunk index is broken); '// &
                            'use --force to start again'
         end if
      end subroutine read_block
      !> '[n1, n2]' in Fortran order (h5py shows the reverse)
      function shape_str(d) result(text)
         integer, intent(in) :: d(:)
         character(len=:), allocatable :: text
         integer :: i
         text = '['//to_str(d(1))
         do i = 2, size(d)
            text = text//', '//to_str(d(i))
         end do
         text = text//']'
      end function shape_str
   end subroutine verify_blocks

   !> "key = a here, key = b in the file" for the first key whose value differs
   !> between two configurations ("key (none)" where one of them lacks it).
   function first_difference(new, old) result(s)
      character(len=*), intent(in) :: new, old  !! configuration texts
      character(len=:), allocatable :: s
      character(len=:), allocatable :: line, key
      character(len=1), parameter :: nl = new_line('a')
      integer :: pass, eol, eq
      ! by key, not by position: the new run's keys in its order, then the keys only
      ! the file has (a line missing in one text must not pair the others wrongly)
      do pass = 1, 2
         if (pass == 1) then
            call walk(new, old)
         else
            call walk(old, new)
         end if
         if (allocated(s)) return
      end do
      s = 'the configurations differ'
   contains
      !> The first line of `text` whose key has another value (or none) in `other`.
      subroutine walk(text, other)
         character(len=*), intent(in) :: text, other
         character(len=:), allocatable :: rest, va, vb
         rest = text//nl
         do
            eol = index(rest, nl)
            if (eol == 0) exit
            line = rest(:eol - 1)
            rest = rest(eol + 1:)
            eq = index(line, ' = ')
            if (eq == 0) cycle
            key = line(:eq - 1)
            va = line(eq + 3:)
            if (.not. has_key(other, key)) then
               vb = '(none)'
            else
               vb = config_value(other, key)
            end if
            if (va == vb) cycle
            if (pass == 1) then
               s = shown(key, va)//' here, '//shown(key, vb)//' in the file'
            else
               s = shown(key, vb)//' here, '//shown(key, va)//' in the file'
            end if
            return
         end do
      end subroutine walk
      !> 'key = value' (`readable`), or 'key (none)' for a key a text lacks.
      function shown(k, v) result(t)
         character(len=*), intent(in) :: k, v
         character(len=:), allocatable :: t
         if (v == '(none)') then
            t = k//' (none)'
         else
            t = readable(k//' = '//v)
         end if
      end function shown
      logical function has_key(text, k)
         character(len=*), intent(in) :: text, k
         has_key = index(nl//text, nl//k//' = ') > 0
      end function has_key
      !> 'key = value' with a stored real (es24.16e3, kept so that older files still
      !> compare equal) shown as real_str shows it: 't_end = 6'.
      function readable(line) result(t)
         character(len=*), intent(in) :: line
         character(len=:), allocatable :: t
         real(dp) :: x
         integer :: eq, stat, comma
         character(len=:), allocatable :: rest, u
         t = line
         eq = index(line, ' = ')
         if (eq == 0) return
         if (index(line(eq + 3:), 'E') == 0) return
         if (verify(trim(line(eq + 3:)), '0123456789.E+-, ') /= 0) return
         ! one real, or a list of reals 'a, b, c' (N links: m, l, q, w)
         rest = line(eq + 3:)
         u = ''
         do
            comma = index(rest, ',')
            if (comma == 0) comma = len(rest) + 1
            read (rest(:comma - 1), *, iostat=stat) x
            if (stat /= 0) return
            u = u//real_str(x)
            if (comma > len(rest)) exit
            u = u//', '
            rest = rest(comma + 1:)
         end do
         t = line(:eq + 2)//u
      end function readable
   end function first_difference

end module dpend_sweep_resume
