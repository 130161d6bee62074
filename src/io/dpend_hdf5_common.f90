!> The helpers that the submodules of dpend_hdf5 share: starting the HDF5 library
!> and turning off its error printing (and the flags that record both), the HDF5
!> types of the elements and strings, closing identifiers, the texts of failures,
!> the check that a file is open, the shape of a dataspace. The interfaces, with the
!> arguments' documentation, are in dpend_hdf5.
submodule (dpend_hdf5) dpend_hdf5_common
   implicit none

   logical, save :: library_ready = .false.  !! h5open_f has been called
   !> HDF5's error printing is off in this thread. The library is thread-safe, so
   !> the setting is per thread: every OpenMP thread that calls HDF5 turns it off.
   logical, save :: thread_quiet = .false.
   !$omp threadprivate(thread_quiet)

contains

   module procedure init_library
      integer :: hdferr
      hdferr = 0
      !$omp critical (dpend_hdf5_init)
      if (.not. library_ready) then
         call h5open_f(hdferr)
         library_ready = hdferr == 0
      end if
      !$omp end critical (dpend_hdf5_init)
      if (hdferr /= 0) then
         call fatal_error(error, 'cannot initialise the HDF5 library')
         return
      end if
      call quiet_thread()
   end procedure init_library

   module procedure quiet_thread
      integer :: ierr
      if (thread_quiet .or. .not. library_ready) return
      call h5eset_auto_f(0, ierr)
      thread_quiet = ierr == 0
   end procedure quiet_thread

   module procedure real_type
      real_type = h5kind_to_type(real64, H5_REAL_KIND)
   end procedure real_type

   module procedure int_type
      int_type = h5kind_to_type(kind(0), H5_INTEGER_KIND)
   end procedure int_type

   module procedure i64_type
      i64_type = h5kind_to_type(i8, H5_INTEGER_KIND)
   end procedure i64_type

   module procedure string_type
      integer :: ierr
      call h5tcopy_f(H5T_NATIVE_CHARACTER, stype, ierr)
      call h5tset_size_f(stype, int(max(1, length), size_t), ierr)
      call h5tset_strpad_f(stype, H5T_STR_NULLPAD_F, ierr)
   end procedure string_type

   module procedure vlen_string_type
      integer :: ierr
      call h5tcopy_f(H5T_STRING, stype, ierr)
      call h5tset_cset_f(stype, H5T_CSET_UTF8_F, ierr)
   end procedure vlen_string_type

   module procedure forget_stored
      integer :: k
      if (.not. allocated(self%stored)) return
      do k = 1, size(self%stored)
         call close_id(self%stored(k)%dset)
         call close_id(self%stored(k)%dtype)
      end do
      deallocate (self%stored)
   end procedure forget_stored

   module procedure close_id
      integer :: id_type, ierr
      if (id < 0) return
      call h5iget_type_f(id, id_type, ierr)
      if (ierr /= 0) id_type = H5I_BADID_F
      if (id_type == H5I_DATASET_F) call h5dclose_f(id, ierr)
      if (id_type == H5I_DATASPACE_F) call h5sclose_f(id, ierr)
      if (id_type == H5I_DATATYPE_F) call h5tclose_f(id, ierr)
      if (id_type == H5I_ATTR_F) call h5aclose_f(id, ierr)
      if (id_type == H5I_GROUP_F) call h5gclose_f(id, ierr)
      if (id_type == H5I_GENPROP_LST_F) call h5pclose_f(id, ierr)
      id = -1
   end procedure close_id

   module procedure quoted
      q = "'"//trim(text)//"'"
   end procedure quoted

   module procedure attr_label
      text = "attribute '"//trim(name)//"' of '"//trim(path)//"'"
   end procedure attr_label

   module procedure label
      if (present(name)) then
         text = attr_label(path, name)
      else
         text = quoted(path)
      end if
   end procedure label

   module procedure fail
      if (allocated(self%filename)) then
         if (verb == 'write' .or. verb == 'create') then
            call fatal_error(error, 'cannot '//verb//' '//what//' in '//quoted(self%filename) &
               //': '//io_failure_reason(self%filename, why))
         else
            call fatal_error(error, 'cannot '//verb//' '//what//' in '//quoted(self%filename) &
               //': '//why)
         end if
      else
         call fatal_error(error, 'cannot '//verb//' '//what//': '//why)
      end if
   end procedure fail

   module procedure require_open
      if (self%is_open()) call quiet_thread()
      if (.not. self%is_open()) then
         call fatal_error(error, 'cannot access '//quoted(path)//': no HDF5 file is open')
      else if (write .and. self%readonly) then
         call fail(error, 'write', self, quoted(path), 'file is open read-only')
      end if
   end procedure require_open

   module procedure space_dims
      integer(hsize_t), allocatable :: maxd(:)
      integer :: rank, ierr
      call h5sget_simple_extent_ndims_f(space, rank, ierr)
      allocate (dims(max(rank, 0)), maxd(max(rank, 0)))
      if (rank > 0) call h5sget_simple_extent_dims_f(space, dims, maxd, ierr)
      if (present(maxdims)) maxdims = maxd
   end procedure space_dims
end submodule dpend_hdf5_common
