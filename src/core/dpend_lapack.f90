!> Explicit interfaces of the LAPACK routines dpend calls (the build uses
!> -Werror=implicit-interface), in one place. Arguments as in the LAPACK 3
!> reference documentation; `info` = 0 on success, < 0: argument -info was illegal.
module dpend_lapack
   use dpend_kinds, only: dp
   implicit none
   private
   public :: dgeqrf, dorgqr, dpotrf, dpotrs, dsygv, dgesv, dgeev, dgetrf, dgetrs

   interface
      !> QR factorization of a general m×n matrix (Householder).
      subroutine dgeqrf(m, n, a, lda, tau, work, lwork, info)
         import :: dp
         integer, intent(in) :: m, n, lda, lwork
         real(dp), intent(inout) :: a(lda, *)
         real(dp), intent(out) :: tau(*)
         real(dp), intent(inout) :: work(*)
         integer, intent(out) :: info
      end subroutine dgeqrf
      !> The m×n matrix Q with orthonormal columns from dgeqrf's reflectors.
      subroutine dorgqr(m, n, k, a, lda, tau, work, lwork, info)
         import :: dp
         integer, intent(in) :: m, n, k, lda, lwork
         real(dp), intent(inout) :: a(lda, *)
         real(dp), intent(in) :: tau(*)
         real(dp), intent(inout) :: work(*)
         integer, intent(out) :: info
      end subroutine dorgqr
      !> Cholesky factorization A = Uᵀ U (uplo 'U') or L Lᵀ (uplo 'L') of a symmetric
      !> positive definite matrix; info > 0: the leading minor of order info is not
      !> positive definite.
      subroutine dpotrf(uplo, n, a, lda, info)
         import :: dp
         character(len=1), intent(in) :: uplo
         integer, intent(in) :: n, lda
         real(dp), intent(inout) :: a(lda, *)
         integer, intent(out) :: info
      end subroutine dpotrf
      !> Solve A X = B with the Cholesky factor of dpotrf.
      subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
         import :: dp
         character(len=1), intent(in) :: uplo
         integer, intent(in) :: n, nrhs, lda, ldb
         real(dp), intent(in) :: a(lda, *)
         real(dp), intent(inout) :: b(ldb, *)
         integer, intent(out) :: info
      end subroutine dpotrs
      !> Generalized symmetric-definite eigenproblem (itype 1: A x = λ B x, B positive
      !> definite); jobz 'V': eigenvectors in a, B-normalised (xᵀ B x = 1); w ascending.
      subroutine dsygv(itype, jobz, uplo, n, a, lda, b, ldb, w, work, lwork, info)
         import :: dp
         integer, intent(in) :: itype, n, lda, ldb, lwork
         character(len=1), intent(in) :: jobz, uplo
         real(dp), intent(inout) :: a(lda, *)
         real(dp), intent(inout) :: b(ldb, *)
         real(dp), intent(out) :: w(*)
         real(dp), intent(inout) :: work(*)
         integer, intent(out) :: info
      end subroutine dsygv
      !> Solve A X = B for a general square A by LU with partial pivoting;
      !> info > 0: U(info, info) is exactly zero.
      subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
         import :: dp
         integer, intent(in) :: n, nrhs, lda, ldb
         real(dp), intent(inout) :: a(lda, *)
         integer, intent(out) :: ipiv(*)
         real(dp), intent(inout) :: b(ldb, *)
         integer, intent(out) :: info
      end subroutine dgesv
      !> LU factorization with partial pivoting of a general m×n matrix;
      !> info > 0: U(info, info) is exactly zero.
      subroutine dgetrf(m, n, a, lda, ipiv, info)
         import :: dp
         integer, intent(in) :: m, n, lda
         real(dp), intent(inout) :: a(lda, *)
         integer, intent(out) :: ipiv(*)
         integer, intent(out) :: info
      end subroutine dgetrf
      !> Solve A X = B (trans 'N') or Aᵀ X = B ('T') with the LU factors of dgetrf.
      subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
         import :: dp
         character(len=1), intent(in) :: trans
         integer, intent(in) :: n, nrhs, lda, ldb
         real(dp), intent(in) :: a(lda, *)
         integer, intent(in) :: ipiv(*)
         real(dp), intent(inout) :: b(ldb, *)
         integer, intent(out) :: info
      end subroutine dgetrs
      !> Eigenvalues (wr + i wi) and, with jobvl/jobvr 'V', left/right eigenvectors of a
      !> general real n×n matrix; a complex pair j, j+1 (wi(j) > 0) has the eigenvector
      !> vr(:, j) + i vr(:, j+1); info > 0: the QR algorithm failed.
      subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, &
                       info)
         import :: dp
         character(len=1), intent(in) :: jobvl, jobvr
         integer, intent(in) :: n, lda, ldvl, ldvr, lwork
         real(dp), intent(inout) :: a(lda, *)
         real(dp), intent(out) :: wr(*), wi(*)
         real(dp), intent(out) :: vl(ldvl, *), vr(ldvr, *)
         real(dp), intent(inout) :: work(*)
         integer, intent(out) :: info
      end subroutine dgeev
   end interface
end module dpend_lapack
