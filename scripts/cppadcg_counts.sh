#!/usr/bin/env bash
# Instructions per call of Pinocchio's code generation (CppADCodeGen) for τ (rnea), the last
# joint's pose and its Jacobian, on the PUMA 560 and Panda models scripts/pinocchio_derivatives.py
# builds (quarter turns made exact), for comparison with `examples/instructions.rs`
# (issue 16 §0). Needs `pip install pin cmeel-cppadcodegen cmeel-eigen` (headers and libraries
# come with the wheels; about a minute to compile the generator). The generated C is compiled with
# gcc -O3 twice: for baseline x86-64 (like `cargo build --release`) and for x86-64-v3 (AVX2,
# like `RUSTFLAGS="-C target-cpu=x86-64-v3"`); each function is called 1,000 times under
# callgrind and its inclusive count (sin, cos and sincos included) divided by 1,000.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${TMPDIR:-/tmp}/dhgen-cppadcg"
source scripts/pinocchio_cxx.sh
extra_libs=(-lcppad_lib)
pinocchio_cxx benches/pinocchio/cppadcg.cpp "$out/generate" -O1 -w
for robot in puma560:6 panda:7; do
    name=${robot%:*}
    dof=${robot#*:}
    "$out/generate" "$out/$name.bin" "$out/$name.c"
    for target in x86-64 x86-64-v3; do
        gcc -O3 -march=$target -fno-inline -c "$out/$name.c" -o "$out/$name.$target.o"
        gcc -O3 -march=$target benches/pinocchio/cppadcg_harness.c "$out/$name.$target.o" -lm \
            -o "$out/$name.$target"
        for f in rnea fk jacobian; do
            valgrind --tool=callgrind --callgrind-out-file="$out/cg.out" \
                "$out/$name.$target" "$dof" "$f" > /dev/null 2>&1
            callgrind_annotate --inclusive=yes "$out/cg.out" | python3 -c '
import re, sys
name, target, f = sys.argv[1:]
for line in sys.stdin:
    m = re.match(r"\s*([\d,]+) .*:(\w+) \[", line)
    if m and m.group(2) == f:
        n = int(m.group(1).replace(",", "")) / 1000
        print(f"{name} {target}: {f} {n:,.0f} instructions per call")
        break
' "$name" "$target" "$f"
        done
    done
done
