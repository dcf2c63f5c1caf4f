#!/usr/bin/env bash
# The wheel stands alone. In a temporary folder: builds the wheel with scripts/build-wheel.sh (pip's own build folder,
# not a CMake build tree), checks with `auditwheel show` that it needs no library outside its manylinux policy, installs
# it with --no-deps into a fresh virtual environment that holds numpy only, checks that ldd resolves every library of
# the installed extension, with LD_LIBRARY_PATH empty, inside the wheel or to a library of the policy's list, and runs
# a copy of the pytest suite against that install (pytest from a folder of its own; neither the source tree nor a build
# tree is on sys.path). The program given is only the reference the suite compares with, run as a separate process.
# Also checks that the type stubs and the shipped network are in the wheel. Prints the wheel's tag, size, bundled
# libraries and install time.
# Usage: python/test-wheel.sh CLOTHCD_PROGRAM
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
cli=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
tools=${CLOTHCD_WHEEL_TOOLS:-$root/build-wheel/tools}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() {
  echo "wheel test: $*" >&2
  exit 1
}

"$root/scripts/build-wheel.sh" "$tmp/dist" > "$tmp/build.log" 2>&1 || {
  cat "$tmp/build.log" >&2
  fail "scripts/build-wheel.sh failed"
}
wheel=$(ls "$tmp"/dist/clothcd-*.whl)
tag=$(basename "$wheel" .whl | cut -d- -f5)

# auditwheel show: the wheel meets the policy of the tag it carries, and needs no library outside it.
"$tools/bin/auditwheel" show "$wheel"
"$tools/bin/auditwheel" show --json "$wheel" 2> /dev/null | "$tools/bin/python" -c '
import json, sys
report, tag = json.load(sys.stdin), sys.argv[1]
consistent, external = report["overall_tag"], ", ".join(report["external_libs"])
if consistent != tag:
    sys.exit(f"wheel test: auditwheel finds the wheel consistent with {consistent}, not with its tag {tag}")
if external:
    sys.exit(f"wheel test: the wheel needs libraries outside its policy: {external}")
' "$tag"

python3 -m venv "$tmp/venv"
venv_python=$tmp/venv/bin/python
"$venv_python" -m pip install --quiet --disable-pip-version-check numpy
start=$(date +%s.%N)
"$venv_python" -m pip install --quiet --disable-pip-version-check --no-deps --no-index "$wheel"
end=$(date +%s.%N)
"$venv_python" -m pip check > /dev/null || fail "the installed wheel's requirements are not met by numpy alone"
site=$("$venv_python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
for file in clothcd/_clothcd.pyi clothcd/py.typed clothcd/models/default/network.xml; do
  [[ -f "$site/$file" ]] || fail "the wheel has no $file"
done

# ldd of the extension: every library inside the installed wheel, the dynamic loader or on the policy's list.
policy_libraries=$("$tools/bin/python" - "$tag" << 'EOF'
import json, pathlib, sys
import auditwheel.policy
policies = json.loads((pathlib.Path(auditwheel.policy.__file__).parent / "manylinux-policy.json").read_text())
name = sys.argv[1].rsplit("_", 2)[0]  # manylinux_2_36_x86_64 -> manylinux_2_36
print("\n".join(next(policy["lib_whitelist"] for policy in policies if policy["name"] == name)))
EOF
)
extension=$(ls "$site"/clothcd/_clothcd*.so)
ldd_output=$(LD_LIBRARY_PATH= ldd "$extension")
echo "ldd $extension:"
echo "$ldd_output"
while read -r name arrow path _; do
  [[ "$name" == linux-vdso.so.* ]] && continue
  [[ "$arrow" != "=>" ]] && continue  # the dynamic loader, named by its path
  [[ "$path" == "$site"/* ]] && continue
  [[ "$path" != "not" ]] || fail "ldd finds no $name"
  grep -qxF "$name" <<< "$policy_libraries" || fail "$name comes from $path, neither the wheel nor the policy's list"
done <<< "$ldd_output"

# The pytest suite, copied beside the project's CMakeLists.txt (the version test reads the version there) and the
# Python examples (a test runs one), run from the copy against the installed package.
mkdir -p "$tmp/suite/python" "$tmp/suite/examples"
cp -r "$root/python/tests" "$tmp/suite/python/tests"
cp -r "$root/examples/python" "$tmp/suite/examples/python"
cp "$root/CMakeLists.txt" "$tmp/suite/"
"$venv_python" -m pip install --quiet --disable-pip-version-check --target "$tmp/pytest" pytest
cd "$tmp/suite"
imported=$(LD_LIBRARY_PATH= "$venv_python" -c 'import clothcd; print(clothcd.__file__)')
[[ "$imported" == "$site"/* ]] || fail "clothcd imported from $imported instead of the fresh environment"
LD_LIBRARY_PATH= PYTHONPATH=$tmp/pytest CLOTHCD_CLI=$cli "$venv_python" -m pytest -q -p no:cacheprovider python/tests

echo "wheel tag: $tag"
echo "wheel size: $(stat -c %s "$wheel") bytes"
echo "bundled libraries: $(cd "$site" && ls clothcd.libs | tr '\n' ' ')"
echo "install time into a fresh environment (numpy already there): $(awk "BEGIN { printf \"%.1f\", $end - $start }") s"
