// The kernel support/simd_versions.hpp compiles for CLOTHCD_SIMD_KERNEL_FUNCTION: run_kernel passes its arguments
// on to that function, which is forced inline and so compiled for the version's level. No include guard, on purpose.

/// CLOTHCD_SIMD_KERNEL_FUNCTION(arguments...) compiled for this version's level.
template <class... Arguments>
decltype(auto) run_kernel(Arguments&&... arguments) {
  return CLOTHCD_SIMD_KERNEL_FUNCTION(std::forward<Arguments>(arguments)...);
}
