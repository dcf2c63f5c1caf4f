// The instruction-set seam's second file (with simd.hpp): compiles one kernel header once per level of
// clothcd::SimdLevel and dispatches to the version of a level, so that a kernel is written once, on the vector layer
// (simd.hpp), and no other file names an instruction set or a target option.
//
// Use, in the .cpp that calls the kernel (which includes support/simd.hpp with its other headers), inside its
// namespace, after the helpers the kernel uses:
//   #define CLOTHCD_SIMD_KERNEL "area/name_kernel.hpp"
//   #include "support/simd_versions.hpp"
// and then CLOTHCD_SIMD_DISPATCH(level, function(arguments)) runs kernel_version::function for `level`. The header
// is included in namespaces baseline_kernels, avx2_kernels and avx512_kernels, each naming its level's lane set
// `lanes` (simd::baseline_lanes, else simd::avx2_lanes) and its level kLevel; every function it defines (lambdas
// included) is compiled for that level, and its entry points, marked CLOTHCD_SIMD_ENTRY, inline every call at the
// wide levels (so that no wide code lands in an inline function the baseline shares). A kernel header has no include
// guard and no includes. Options, defined beside CLOTHCD_SIMD_KERNEL (and undefined here after use):
//   CLOTHCD_SIMD_KERNEL_AVX512  an AVX-512 version too; without it, AVX-512 runs the AVX2 version.
//   CLOTHCD_SIMD_KERNEL_WIDE    only the wide versions (written on simd::avx2_lanes): the caller keeps the baseline
//                               as its own code, beside it, and runs the two with CLOTHCD_SIMD_DISPATCH_WIDE(level,
//                               wide_call, baseline_call). Off x86-64 the kernel is not compiled at all.
// A kernel written lane by lane (on simd::LaneArray, or plain loops), which the compiler vectorizes at each level,
// needs no header of its own: define CLOTHCD_SIMD_KERNEL_FUNCTION as its name instead of CLOTHCD_SIMD_KERNEL (a
// function, or function template, forced inline, in the including namespace); each version then defines run_kernel,
// which passes its arguments on to it, so that CLOTHCD_SIMD_DISPATCH(level, run_kernel(arguments)) runs it compiled
// for `level`.
// One kernel per .cpp (the namespaces' names are fixed).
#if defined(CLOTHCD_SIMD_KERNEL_FUNCTION)
#define CLOTHCD_SIMD_KERNEL "support/simd_function_kernel.hpp"
#elif !defined(CLOTHCD_SIMD_KERNEL)
#error "define CLOTHCD_SIMD_KERNEL or CLOTHCD_SIMD_KERNEL_FUNCTION before including support/simd_versions.hpp"
#endif

#if !defined(CLOTHCD_SIMD_VERSION_OPEN)
/// Opens the namespace `name` of one version (closed by the including code): its lane set, `lanes`
/// (simd::lane_set), and its level, kLevel (SimdLevel::level).
#define CLOTHCD_SIMD_VERSION_OPEN(name, lane_set, level)        \
  namespace name {                                              \
  namespace lanes = ::clothcd::simd::lane_set;                  \
  [[maybe_unused]] constexpr ::clothcd::SimdLevel kLevel = ::clothcd::SimdLevel::level;
#endif

#if !defined(CLOTHCD_SIMD_KERNEL_WIDE)
#define CLOTHCD_SIMD_ENTRY
CLOTHCD_SIMD_VERSION_OPEN(baseline_kernels, baseline_lanes, Baseline)
#include CLOTHCD_SIMD_KERNEL
}  // namespace baseline_kernels
#undef CLOTHCD_SIMD_ENTRY
#endif

#if defined(CLOTHCD_SIMD_X86)
#define CLOTHCD_SIMD_ENTRY __attribute__((flatten))
CLOTHCD_SIMD_BEGIN_AVX2
CLOTHCD_SIMD_VERSION_OPEN(avx2_kernels, avx2_lanes, Avx2)
#include CLOTHCD_SIMD_KERNEL
}  // namespace avx2_kernels
CLOTHCD_SIMD_END
#if defined(CLOTHCD_SIMD_KERNEL_AVX512)
CLOTHCD_SIMD_BEGIN_AVX512
CLOTHCD_SIMD_VERSION_OPEN(avx512_kernels, avx2_lanes, Avx512)
#include CLOTHCD_SIMD_KERNEL
}  // namespace avx512_kernels
CLOTHCD_SIMD_END
#else
namespace avx512_kernels = avx2_kernels;
#endif
#undef CLOTHCD_SIMD_ENTRY
#elif !defined(CLOTHCD_SIMD_KERNEL_WIDE)
namespace avx2_kernels = baseline_kernels;
namespace avx512_kernels = baseline_kernels;
#endif

#if !defined(CLOTHCD_SIMD_DISPATCH)
/// `call` (a call of a kernel function, written without namespace) in the kernel version for `level`, one of
/// cpu_simd_levels().
#define CLOTHCD_SIMD_DISPATCH(level, ...)                                                                           \
  ((level) == ::clothcd::SimdLevel::Avx512 ? avx512_kernels::__VA_ARGS__                                            \
   : (level) == ::clothcd::SimdLevel::Avx2 ? avx2_kernels::__VA_ARGS__                                              \
                                           : baseline_kernels::__VA_ARGS__)
#if defined(CLOTHCD_SIMD_X86)
/// `wide_call` in the wide kernel version for `level` (AVX2 or AVX-512), else `baseline_call`, the caller's own code.
#define CLOTHCD_SIMD_DISPATCH_WIDE(level, wide_call, baseline_call)                                                 \
  ((level) == ::clothcd::SimdLevel::Avx512 ? avx512_kernels::wide_call                                              \
   : (level) == ::clothcd::SimdLevel::Avx2 ? avx2_kernels::wide_call                                                \
                                           : baseline_call)
#else
#define CLOTHCD_SIMD_DISPATCH_WIDE(level, wide_call, baseline_call) ((void)(level), baseline_call)
#endif
#endif

#undef CLOTHCD_SIMD_KERNEL
#undef CLOTHCD_SIMD_KERNEL_FUNCTION
#undef CLOTHCD_SIMD_KERNEL_AVX512
#undef CLOTHCD_SIMD_KERNEL_WIDE
