# Compiler flag sets used by every script, so build, run and test share one build
# directory per profile. Source it: . scripts/flags.sh
# Release: vectorized libmvec sin/cos need -fno-math-errno -fno-trapping-math.
# Never -ffast-math: the symplectic methods rely on compensated summation.
DEBUG_FLAGS="-g -fbacktrace -fcheck=all -ffpe-trap=invalid,zero,overflow -Wall -Wextra -Wcharacter-truncation"
RELEASE_FLAGS="-O3 -march=native -fno-math-errno -fno-trapping-math -fopenmp"
export DEBUG_FLAGS RELEASE_FLAGS
