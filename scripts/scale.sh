#!/usr/bin/env bash
# The cost of generating and compiling random arms against their size: for each style
# (general: no exact angles; industrial: twists in {0, ±90°}) and number of joints, the
# generator's time unoptimised (the debug `dhgen` runs the generator as an unoptimised proc
# macro does), its peak memory, the operations per generated function, and (with
# `--compile`) the release build time of a crate holding only that robot.
#
#   scripts/scale.sh [--compile] [N ...]        (default N: 6 8 10 12 16 20 30)
#
# Output: Markdown tables on stdout; scratch files in target/scale/.
set -euo pipefail
cd "$(dirname "$0")/.."
compile=false
if [[ "${1:-}" == "--compile" ]]; then compile=true; shift; fi
sizes=("$@")
[[ ${#sizes[@]} -gt 0 ]] || sizes=(6 8 10 12 16 20 30)
out=target/scale
mkdir -p "$out"
cargo build -q -p dhgen-cli
dhgen=target/debug/dhgen
if $compile; then
  crate="$out/crate"
  mkdir -p "$crate/src"
  cat > "$crate/Cargo.toml" <<TOML
[package]
name = "scale"
version = "0.0.0"
edition = "2024"
publish = false
[dependencies]
dhgen = { path = "$(pwd)", default-features = false }
[workspace]
TOML
  echo 'pub fn nothing() {}' > "$crate/src/lib.rs"
  (cd "$crate" && cargo build -q --release)
fi
echo "| style | joints | generation, unoptimised (s) | peak memory (MB) | statements | D | c_ijk | C | g | τ | release build (s) |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for style in general industrial; do
  for n in "${sizes[@]}"; do
    file="$out/${style}_$n.toml"
    "$dhgen" random --dof "$n" --style "$style" --seed 1 -o "$file"
    report=$( { /usr/bin/time -f "RSS %M" "$dhgen" ops "$file"; } 2>&1 )
    ms=$(echo "$report" | sed -n 's/.*generated in \([0-9.]*\) ms.*/\1/p')
    statements=$(echo "$report" | sed -n 's/.*~\([0-9]*\) statements.*/\1/p')
    rss=$(echo "$report" | sed -n 's/^RSS \([0-9]*\)/\1/p')
    ops() { echo "$report" | awk -v f="$1" -F'│' '{gsub(/ /,"",$2)} $2==f {gsub(/ /,"",$7); print $7}'; }
    build="-"
    if $compile; then
      cp "$file" "$out/crate/robot.toml"
      printf '#![no_std]\ndhgen::robot!(pub mod arm = "robot.toml");\n' > "$out/crate/src/lib.rs"
      start=$(date +%s.%N)
      (cd "$out/crate" && cargo build -q --release)
      build=$(echo "$(date +%s.%N) - $start" | bc | xargs printf '%.0f')
    fi
    printf '| %s | %d | %.2f | %d | %s | %s | %s | %s | %s | %s | %s |\n' "$style" "$n" \
      "$(echo "$ms / 1000" | bc -l)" "$((rss / 1024))" "$statements" \
      "$(ops mass_matrix)" "$(ops christoffel)" "$(ops coriolis)" "$(ops gravity)" \
      "$(ops inverse_dynamics_smooth)" "$build"
  done
done
