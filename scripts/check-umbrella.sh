#!/usr/bin/env bash
# Checks that the umbrella header include/clothcd/clothcd.hpp includes every public header of clothcd::core (every
# header under include/clothcd/ but the training side's clothcd/learning/, and the generated clothcd/version.hpp), and
# nothing else.
# Usage: scripts/check-umbrella.sh [SOURCE_DIR]
set -euo pipefail
root="${1:-$(cd "$(dirname "$0")/.." && pwd)}"
cd "$root/include"

expected=$( { echo clothcd/version.hpp; find clothcd -name '*.hpp' ! -path 'clothcd/learning/*' ! -path clothcd/clothcd.hpp; } | sort)
listed=$(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\(clothcd\/[^"]*\)".*/\1/p' clothcd/clothcd.hpp | sort)

missing=$(comm -23 <(echo "$expected") <(echo "$listed"))
extra=$(comm -13 <(echo "$expected") <(echo "$listed"))
[[ -n "$missing" ]] && echo "clothcd/clothcd.hpp does not include:" $missing >&2
[[ -n "$extra" ]] && echo "clothcd/clothcd.hpp includes headers that are not public core headers:" $extra >&2
if [[ -n "$missing$extra" ]]; then exit 1; fi
echo "check-umbrella: clothcd/clothcd.hpp includes the $(echo "$expected" | wc -l) public core headers"
