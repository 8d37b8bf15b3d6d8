#!/usr/bin/env bash
# Times Pinocchio's rnea, computeRNEADerivatives and computeABADerivatives on the same PUMA 560
# and Panda models as scripts/pinocchio_derivatives.py builds (from tests/data), for comparison
# with `cargo bench --bench derivatives`. Needs `pip install pin cmeel-eigen` (Pinocchio's
# headers and libraries come with the wheels); compiles benches/pinocchio/derivatives.cpp with
# -O3 -march=native and Pinocchio's templates instantiated here (about 4 minutes).
# `--callgrind` instead counts instructions per call (exact, load-independent): compiled for
# baseline x86-64 like `cargo build --release` (valgrind has no AVX-512), each function called
# 1,000 times under callgrind, its inclusive count divided by its calls;
# `--callgrind -march=x86-64-v3` counts the build for AVX2 and FMA instead (to compare with
# dhgen built with `RUSTFLAGS="-C target-cpu=x86-64-v3"`).
# `--time FLAGS` times a build with FLAGS instead of -march=native: `--time ""` for baseline
# x86-64 (like `cargo bench`), `--time -march=x86-64-v3` (like dhgen's x86-64-v3 build).
# Timing builds also benches/pinocchio/task_space.cpp (the tool's task-space dynamics as a
# Pinocchio user writes them, about 2 more minutes) and times it, for comparison with
# `cargo bench --bench generated -- task_space`.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${TMPDIR:-/tmp}/dhgen-pinocchio-bench"
source scripts/pinocchio_cxx.sh
march=-march=native
[[ "${1:-}" == --callgrind || "${1:-}" == --time ]] && march="${2:-}"
pinocchio_cxx benches/pinocchio/derivatives.cpp "$out/bench" -O3 $march
if [[ "${1:-}" != --callgrind ]]; then
    "$out/bench" "$out/puma560.bin" "$out/panda.bin"
    pinocchio_cxx benches/pinocchio/task_space.cpp "$out/task_space" -O3 $march
    "$out/task_space" "$out/puma560.bin" "$out/panda.bin"
    exit
fi
for name in puma560 panda; do
    DHGEN_PIN_CALLS=1000 valgrind --tool=callgrind --callgrind-out-file="$out/$name.callgrind" \
        "$out/bench" "$out/$name.bin" > /dev/null 2>&1
    callgrind_annotate --inclusive=yes "$out/$name.callgrind" | python3 -c '
import re, sys
name = sys.argv[1]
# rnea also runs 64 times to make the torques computeABADerivatives starts from.
calls = {"rnea": 1064, "computeRNEADerivatives": 1000, "computeABADerivatives": 1000}
for line in sys.stdin:
    m = re.match(r"\s*([\d,]+) .*pinocchio::impl::(\w+)<", line)
    if m and m.group(2) in calls:
        n = int(m.group(1).replace(",", "")) / calls.pop(m.group(2))
        print(f"{name}: {m.group(2)} {n:,.0f} instructions per call")
' "$name"
done
