#!/usr/bin/env bash
# Checks the libraries' area graph: every #include "..." in src/<area>/ and include/clothcd/<area>/ may name a public
# header (include/clothcd/<area>/...) of its own area or of a lower one; a file under src/ may also name a private
# header (src/<area>/...) of its own area or of a lower one, and a public header includes no private header at all.
# Order, lowest first: support (include/clothcd/*.hpp and src/support/, e.g. the vector layer simd.hpp) < mesh <
# geometry, render < broadphase < ccd < detection < simulation < culling (the run-time pair network plugs into the
# detector from above, as its PairCuller) < learning (training, the one area of clothcd::learning; dataset generation
# drives detectors). Any other include fails. The umbrella header include/clothcd/clothcd.hpp is above them all.
# No public header may reach a compiler intrinsics header (immintrin.h, emmintrin.h, arm_neon.h, ...) or name
# vector-extension types: the SIMD code stays inside src/ (Eigen, a dependency, includes its own). Instruction sets have one seam: only src/support/simd.hpp, simd_versions.hpp and simd_level.cpp
# may name the target macros (CLOTHCD_SIMD_X86, CLOTHCD_SIMD_AVX2, CLOTHCD_SIMD_BEGIN_*, CLOTHCD_SIMD_END), a target
# attribute or pragma, or a compiler's instruction-set macro (__AVX2__, __SSE2__, __ARM_NEON, ...); every other file
# writes its kernels on the vector layer and dispatches through simd_versions.hpp.
# Usage: scripts/check-includes.sh [SOURCE_DIR]
set -euo pipefail
root="${1:-$(cd "$(dirname "$0")/.." && pwd)}"
cd "$root"

rank() {
  case "$1" in
    support) echo 0 ;;
    mesh) echo 1 ;;
    geometry | render) echo 2 ;;
    broadphase) echo 3 ;;
    ccd) echo 4 ;;
    detection) echo 5 ;;
    simulation) echo 6 ;;
    culling) echo 7 ;;
    learning) echo 8 ;;
    *) echo "unknown area '$1'" >&2; exit 2 ;;
  esac
}

failures=0
while IFS= read -r file; do
  if [[ "$file" == include/clothcd/*/* ]]; then
    area="${file#include/clothcd/}"
    area="${area%%/*}"
  elif [[ "$file" == include/clothcd/* ]]; then
    area=support
  else
    area="${file#src/}"
    area="${area%%/*}"
  fi
  [[ "$file" == include/clothcd/clothcd.hpp ]] && continue  # the umbrella header includes every area
  [[ "$area" == support ]] || [[ -d "src/$area" ]] || continue
  while IFS= read -r header; do
    if [[ "$header" == clothcd/*/* ]]; then
      target="${header#clothcd/}"
      target="${target%%/*}"
      private=0
    elif [[ "$header" == clothcd/* ]]; then
      target=support
      private=0
    elif [[ "$header" == */* ]]; then
      target="${header%%/*}"
      private=1
    else
      continue  # a header beside the file
    fi
    if ((private)) && [[ "$file" == include/* ]]; then
      echo "$file: includes $header, a private header, from a public header" >&2
      failures=$((failures + 1))
    elif (($(rank "$target") > $(rank "$area"))); then
      echo "$file: includes $header ($target is above $area)" >&2
      failures=$((failures + 1))
    fi
  done < <(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "$file")
done < <(find src include -name '*.hpp' -o -name '*.cpp' -o -name '*.h' | sort)

# Intrinsics and vector-extension types in public headers (with the check above, no public header reaches one
# through a header of ours).
while IFS= read -r hit; do
  echo "$hit: SIMD intrinsics or vector types in a public header (keep them in src/, see src/support/simd.hpp)" >&2
  failures=$((failures + 1))
done < <(grep -rnE '#[[:space:]]*include[[:space:]]*<[a-z0-9_]*(intrin|mmintrin|neon|sve|altivec|vecintrin)[a-z0-9_]*\.h>|vector_size|__m(64|128|256|512)|ext_vector_type' include || true)

# Instruction-set names outside the seam.
while IFS= read -r hit; do
  echo "$hit: names an instruction set outside the seam (src/support/simd.hpp, simd_versions.hpp, simd_level.cpp)" >&2
  failures=$((failures + 1))
done < <(grep -rnE 'CLOTHCD_SIMD_(X86|AVX2|AVX512|BEGIN_[A-Z0-9_]*|END)\b|target[[:space:]]*\(|__(AVX|SSE|ARM_NEON|FMA|BMI)[A-Z0-9_]*__|#[[:space:]]*include[[:space:]]*<[a-z0-9_]*(intrin|neon)[a-z0-9_]*\.h>' \
  src include tools python tests bench fuzz --include='*.hpp' --include='*.cpp' --include='*.h' --include='*.cc' \
  | grep -vE '^src/support/(simd\.hpp|simd_versions\.hpp|simd_level\.cpp):' || true)

if ((failures)); then
  echo "check-includes: $failures include(s) or instruction-set name(s) against the rules" >&2
  exit 1
fi
echo "check-includes: the area graph and the instruction-set seam hold"
