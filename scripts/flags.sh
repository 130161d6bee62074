# Compiler flag sets used by every script, so build, run and test share one build
# directory per profile. Source it: . scripts/flags.sh
# Release: vectorized libmvec sin/cos need -fno-math-errno -fno-trapping-math.
# Never -ffast-math: the symplectic methods rely on compensated summation.
# Debug: warnings on; each -Wno- class has its reason in docs/architecture.md ("Warnings").
DEBUG_FLAGS="-g -fbacktrace -fcheck=all -ffpe-trap=invalid,zero,overflow"
DEBUG_FLAGS="$DEBUG_FLAGS -Wall -Wextra -Wcharacter-truncation -Wimplicit-procedure -Wpedantic"
DEBUG_FLAGS="$DEBUG_FLAGS -Wno-maybe-uninitialized -Wno-uninitialized -Wno-unused-dummy-argument"
DEBUG_FLAGS="$DEBUG_FLAGS -Wno-compare-reals -Wno-do-subscript"
RELEASE_FLAGS="-O3 -march=native -fno-math-errno -fno-trapping-math -fopenmp"
export DEBUG_FLAGS RELEASE_FLAGS
