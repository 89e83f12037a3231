#!/usr/bin/env bash
# Build scripts/bench_pinocchio.cpp against the C++ library of the `pin` wheel and run it on the
# committed URDFs of the built-in robots. Needs the wheel (scripts/install_pinocchio.sh puts it
# into a venv) and g++. The Python that has it: $OSRL_PIN_PYTHON, else python3.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
py=${OSRL_PIN_PYTHON:-python3}
prefix=$("$py" -c "import cmeel, os; print(os.path.join(os.path.dirname(os.path.dirname(cmeel.__file__)), 'cmeel.prefix'))")
[ -d "$prefix/include/pinocchio" ] || { echo "no Pinocchio headers under $prefix (pip install pin)" >&2; exit 1; }
[ -d "$prefix/include/eigen3" ] || { echo "no Eigen headers under $prefix (pip install cmeel-eigen)" >&2; exit 1; }
out=${TMPDIR:-/tmp}/osrl_bench_pinocchio
src="$root/scripts/bench_pinocchio.cpp"
# Rebuild only when the source changed (the build takes a minute).
if [ ! -x "$out" ] || [ "$src" -nt "$out" ]; then
  g++ -O3 -DNDEBUG -std=c++17 "$src" -o "$out" \
    -I"$prefix/include" -I"$prefix/include/eigen3" -I"$prefix/include/urdfdom_headers" -I"$prefix/include/urdfdom" \
    -DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION -DPINOCCHIO_WITH_URDFDOM -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
    -L"$prefix/lib" -Wl,-rpath,"$prefix/lib" -lpinocchio_default -lpinocchio_parsers -lurdfdom_model
fi
fix="$root/crates/dynamics/tests/fixtures"
"$out" sarcos7 "$fix/sarcos7.urdf" planar3 "$fix/planar3.urdf"
