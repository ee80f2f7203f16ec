# Instruction set of the build machine. With AVX2/FMA instead of the x86-64 baseline (SSE2)
# the patch corrections applied in every GMRES product run 1.2-1.3x faster and the periodic
# Ewald products 1.1x (bench_quadrature); a tube27 step takes 7-8% less time. The simulator is
# built where it runs. Turn RBCFLOW_NATIVE off for a binary that must run on other CPUs (a
# package, a heterogeneous cluster).
# AVX-512 stays off: GCC 12's AVX-512 headers raise false "may be used uninitialized" warnings
# inside Eigen's reductions under -Werror (with it the corrections were another 10-18% faster).
include(CheckCXXCompilerFlag)
if(RBCFLOW_NATIVE)
  check_cxx_compiler_flag(-march=native RBCFLOW_HAS_MARCH_NATIVE)
  check_cxx_compiler_flag(-mno-avx512f RBCFLOW_HAS_NO_AVX512)  # x86 only
  if(RBCFLOW_HAS_MARCH_NATIVE)
    add_compile_options(-march=native $<$<BOOL:${RBCFLOW_HAS_NO_AVX512}>:-mno-avx512f>)
  else()
    message(STATUS "rbcflow: the compiler does not take -march=native; building for the baseline instruction set")
  endif()
endif()
