#!/usr/bin/env bash
# Build scripts/bench_pinocchio.cpp against the C++ library of the `pin` wheel and run it on the
# committed URDFs of the built-in robots. Needs: pip install pin cmeel-eigen cmeel-urdfdom-headers; g++.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
prefix=$(python3 -c "import cmeel, os; print(os.path.join(os.path.dirname(os.path.dirname(cmeel.__file__)), 'cmeel.prefix'))")
out=${TMPDIR:-/tmp}/osrl_bench_pinocchio
g++ -O3 -DNDEBUG -std=c++17 "$root/scripts/bench_pinocchio.cpp" -o "$out" \
  -I"$prefix/include" -I"$prefix/include/eigen3" -I"$prefix/include/urdfdom_headers" -I"$prefix/include/urdfdom" \
  -DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION -DPINOCCHIO_WITH_URDFDOM -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
  -L"$prefix/lib" -Wl,-rpath,"$prefix/lib" -lpinocchio_default -lpinocchio_parsers -lurdfdom_model
fix="$root/crates/dynamics/tests/fixtures"
"$out" sarcos7 "$fix/sarcos7.urdf" planar3 "$fix/planar3.urdf"
