#!/usr/bin/env bash
# Times Pinocchio's rnea, computeRNEADerivatives and computeABADerivatives on the same PUMA 560
# and Panda models as scripts/pinocchio_derivatives.py builds (from tests/data), for comparison
# with `cargo bench --bench derivatives`. Needs `pip install pin cmeel-eigen` (Pinocchio's
# headers and libraries come with the wheel); compiles benches/pinocchio/derivatives.cpp with
# -O3 -march=native and Pinocchio's templates instantiated here (about 4 minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${TMPDIR:-/tmp}/dhgen-pinocchio-bench"
mkdir -p "$out"
python3 - "$out" <<'PY'
import json, sys
from pathlib import Path
sys.path.insert(0, "scripts")
import pinocchio_derivatives as pd
for name in ["puma560", "panda"]:
    robot = json.loads((pd.DATA / f"{name}.json").read_text())
    pd.model_of(robot).saveToBinary(f"{sys.argv[1]}/{name}.bin")
PY
prefix="$(python3 -c 'import pinocchio, pathlib; print(pathlib.Path(pinocchio.__file__).parents[4])')"
g++ -O3 -march=native -DNDEBUG -std=c++17 \
    -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
    -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
    -I"$prefix/include" -I"$prefix/include/eigen3" benches/pinocchio/derivatives.cpp \
    -o "$out/bench" -L"$prefix/lib" -lpinocchio_default -lboost_serialization \
    -lboost_filesystem -Wl,-rpath,"$prefix/lib"
"$out/bench" "$out/puma560.bin" "$out/panda.bin"
