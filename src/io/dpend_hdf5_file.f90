!> The file side of dpend_hdf5: `open`, `close` and `flush` of an `h5file_t`, and
!> what the file holds: `exists`, `attr_exists`, `shape`, `filters` and `datasets`.
!> The interfaces, with the arguments' documentation, are in dpend_hdf5.
submodule (dpend_hdf5) dpend_hdf5_file
   implicit none

contains

   module procedure file_open
      integer(hid_t) :: fapl, fid
      integer :: hdferr, ierr
      logical :: on_disk
      character(len=:), allocatable :: why

      call self%close()
      if (allocated(self%error)) deallocate (self%error)
      call init_library(error)
      if (allocated(error)) return
      if ((mode == 'w' .or. mode == 'x') .and. capturing_outputs() .and. &
          recording_outputs()) then   ! a library call's output, recorded (no HDF5 file)
         allocate (self%record)
         self%filename = trim(filename)
         self%readonly = .false.
         self%memory = .true.
         return
      end if
      inquire (file=filename, exist=on_disk)
      if (present(access)) then
         call h5pcopy_f(access, fapl, ierr)
      else
         call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, ierr)
      end if
      call h5pset_fclose_degree_f(fapl, H5F_CLOSE_STRONG_F, ierr)
      hdferr = -1
      why = io_failure_reason(filename, 'cannot create it')
      select case (mode)
      case ('r', 'rw')
         if (on_disk) then
            why = 'not an HDF5 file or not '//merge('readable', 'writable', mode == 'r')
            call h5fopen_f(trim(filename), merge(H5F_ACC_RDONLY_F, H5F_ACC_RDWR_F, mode == 'r'), &
               fid, hdferr, access_prp=fapl)
         else if (mode == 'r') then
            why = 'no such file'
         else
            call h5fcreate_f(trim(filename), H5F_ACC_EXCL_F, fid, hdferr, access_prp=fapl)
         end if
      case ('w', 'x')
         if (capturing_outputs()) then
            ! a library call's output: in memory (no backing store), whatever is on disk;
            ! grown 16 MiB at a time (a trajectory of 10^5 samples is 48 MB)
            call h5pset_fapl_core_f(fapl, 16777216_size_t, .false., ierr)
            call h5fcreate_f(trim(filename), H5F_ACC_TRUNC_F, fid, hdferr, access_prp=fapl)
            self%memory = hdferr == 0
         else if (mode == 'x' .and. on_disk) then
            why = 'file exists'
         else
            call h5fcreate_f(trim(filename), merge(H5F_ACC_TRUNC_F, H5F_ACC_EXCL_F, mode == 'w'), &
               fid, hdferr, access_prp=fapl)
         end if
      case default
         why = "invalid mode '"//mode//"' (use 'r', 'w', 'rw' or 'x')"
      end select
      call h5pclose_f(fapl, ierr)
      if (hdferr /= 0) then
         call fatal_error(error, 'cannot open '//quoted(filename)//': '//why)
         return
      end if
      self%id = fid
      self%filename = trim(filename)
      self%readonly = mode == 'r'
      self%direct = .not. present(access) .and. .not. self%memory
   end procedure file_open

   module procedure file_close
      integer :: ierr, kerr
      logical :: valid
      if (present(error)) call self%take_error(error)
      if (allocated(self%error)) deallocate (self%error)
      if (allocated(self%record)) then   ! kept for take_record
         call keep_record(self%record)
         self%memory = .false.
         return
      end if
      if (self%id < 0) return
      call quiet_thread()
      call forget_stored(self)
      ierr = 0
      call h5iis_valid_f(self%id, valid, ierr)
      if (valid .and. ierr == 0) then
         kerr = 0
         if (self%memory) call keep_image(self%id, kerr)
         call h5fclose_f(self%id, ierr)
         if (kerr /= 0) ierr = kerr
      end if
      if (ierr /= 0 .and. present(error)) then
         if (.not. allocated(error)) call fatal_error(error, 'cannot close '// &
            quoted(self%filename)//': '//io_failure_reason(self%filename, &
            'HDF5 could not flush it'))
      end if
      self%id = -1
      self%readonly = .false.
      self%memory = .false.
      self%direct = .false.
   end procedure file_close

   !> The image of the in-memory file `fid` into the capture buffer of this thread
   !> (`capture_buffer`); ierr nonzero when it could not be taken.
   subroutine keep_image(fid, ierr)
      integer(hid_t), intent(in) :: fid
      integer, intent(out) :: ierr
      integer(size_t) :: n
      type(c_ptr) :: buf
      call h5fflush_f(fid, H5F_SCOPE_GLOBAL_F, ierr)
      if (ierr /= 0) return
      buf = c_null_ptr
      call h5fget_file_image_f(fid, buf, 0_size_t, ierr, n)
      if (ierr /= 0) return
      buf = capture_buffer(int(n, c_size_t))
      if (.not. c_associated(buf)) then
         ierr = -1
         return
      end if
      call h5fget_file_image_f(fid, buf, n, ierr)
   end subroutine keep_image

   module procedure file_flush
      integer :: ierr
      if (.not. self%is_open()) return
      call quiet_thread()
      call h5fflush_f(self%id, H5F_SCOPE_GLOBAL_F, ierr)
   end procedure file_flush

   module procedure file_exists
      integer :: i, n, ierr
      found = .false.
      if (.not. self%is_open() .or. len_trim(path) == 0) return
      if (allocated(self%record)) then
         found = self%record%has_object(path)
         return
      end if
      found = .true.
      n = len_trim(path)
      do i = 2, n + 1   ! check path(1:i-1) at every component end
         if (i <= n) then
            if (path(i:i) /= '/') cycle
         end if
         if (path(i - 1:i - 1) == '/') cycle
         call h5lexists_f(self%id, path(1:i - 1), found, ierr)
         if (ierr /= 0) found = .false.
         if (.not. found) return
      end do
   end procedure file_exists

   module procedure file_attr_exists
      integer :: ierr
      found = .false.
      if (.not. self%exists(path)) return
      if (allocated(self%record)) then
         found = self%record%find(path, name) > 0
         return
      end if
      call h5aexists_by_name_f(self%id, trim(path), trim(name), found, ierr)
      if (ierr /= 0) found = .false.
   end procedure file_attr_exists

   module procedure file_shape
      integer(hid_t) :: dset
      integer(hsize_t), allocatable :: hdims(:)
      call open_read(self, path, -1, want_any, dset, hdims, error)
      call close_id(dset)
      if (allocated(error)) return
      if (any(hdims > int(huge(1), hsize_t))) then
         call fail(error, 'read', self, quoted(path), 'a dimension of '// &
                   to_str(int(maxval(hdims), i8))//' exceeds '//to_str(max_read_values)// &
                   ' (a size declared by the file is checked before reading)')
         return
      end if
      dims = int(hdims)
   end procedure file_shape

   module procedure file_filters
      integer(hid_t) :: dset, dcpl
      integer(hsize_t), allocatable :: hdims(:)
      integer :: ierr
      n = 0
      call open_read(self, path, -1, want_any, dset, hdims, error)
      if (allocated(error)) return
      call h5dget_create_plist_f(dset, dcpl, ierr)
      if (ierr == 0) then
         call h5pget_nfilters_f(dcpl, n, ierr)
         call h5pclose_f(dcpl, ierr)
      end if
      call close_id(dset)
   end procedure file_filters

   module procedure file_chunks
      interface
         integer(c_int) function c_num_chunks(dset, fspace, nchunks) &
            bind(C, name='H5Dget_num_chunks')   ! HDF5 1.10.5 on
            import :: c_int, c_int64_t
            integer(c_int64_t), value :: dset, fspace   ! hid_t
            integer(c_int64_t), intent(out) :: nchunks  ! hsize_t
         end function c_num_chunks
      end interface
      integer(hid_t) :: dset, space
      integer(hsize_t), allocatable :: hdims(:)
      integer(c_int64_t) :: nchunks
      integer :: ierr
      n = 0
      call open_read(self, path, -1, want_any, dset, hdims, error)
      if (allocated(error)) return
      call h5dget_space_f(dset, space, ierr)   ! (HDF5 1.10.8 refuses H5S_ALL here)
      if (ierr /= 0 .or. c_num_chunks(int(dset, c_int64_t), int(space, c_int64_t), &
                                      nchunks) < 0) then
         call fail(error, 'read the chunk index of', self, quoted(path), 'HDF5 refused it')
      else
         n = int(nchunks, i8)
      end if
      call close_id(space)
      call close_id(dset)
   end procedure file_chunks

   module procedure file_datasets
      character(len=1024), allocatable :: found(:)
      integer :: n, i, width
      allocate (found(16))
      n = 0
      call require_open(self, group, .false., error)
      if (allocated(error)) return
      if (.not. self%exists(group)) then
         call fail(error, 'list', self, quoted(group), 'no such group')
         return
      end if
      call visit(trim(group))
      if (allocated(error)) return
      width = 1
      do i = 1, n
         width = max(width, len_trim(found(i)))
      end do
      allocate (character(len=width) :: paths(n))
      do i = 1, n
         paths(i) = found(i)
      end do
   contains
      !> Append the datasets of group `g` and of the groups below it.
      recursive subroutine visit(g)
         character(len=*), intent(in) :: g
         character(len=1024) :: name
         character(len=:), allocatable :: child
         character(len=1024), allocatable :: more(:)
         integer(hid_t) :: obj
         integer(size_t) :: name_len
         integer :: storage, nlinks, max_corder, ierr, id_type, k
         call h5gget_info_by_name_f(self%id, g, storage, nlinks, max_corder, ierr)
         if (ierr /= 0) then
            call fail(error, 'list', self, quoted(g), 'not a group')
            return
         end if
         do k = 0, nlinks - 1
            name = ''
            call h5lget_name_by_idx_f(self%id, g, H5_INDEX_NAME_F, H5_ITER_INC_F, &
               int(k, hsize_t), name, ierr, name_len)
            if (ierr /= 0) cycle
            if (g == '/') then
               child = '/'//name(1:min(int(name_len), len(name)))
            else
               child = g//'/'//name(1:min(int(name_len), len(name)))
            end if
            call h5oopen_f(self%id, child, obj, ierr)
            if (ierr /= 0) cycle
            call h5iget_type_f(obj, id_type, ierr)
            call h5oclose_f(obj, ierr)
            if (id_type == H5I_GROUP_F) then
               call visit(child)
               if (allocated(error)) return
            else if (id_type == H5I_DATASET_F) then
               if (n == size(found)) then
                  allocate (more(2*n))
                  more(1:n) = found
                  call move_alloc(more, found)
               end if
               n = n + 1
               found(n) = child
            end if
         end do
      end subroutine visit
   end procedure file_datasets
end submodule dpend_hdf5_file
