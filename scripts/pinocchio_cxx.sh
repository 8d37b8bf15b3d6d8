# Sourced by the scripts that build C++ against the Pinocchio wheel (pinocchio_bench.sh,
# cppadcg_counts.sh): from the repository root, with `out` set, saves the PUMA 560 and Panda
# models as `$out/<robot>.bin` and defines `pinocchio_cxx SOURCE OUTPUT FLAGS...`, which compiles
# SOURCE with Pinocchio's, Eigen's and Boost's headers and links it with Pinocchio, Boost and the
# libraries in the array `extra_libs` (the headers and libraries come with
# `pip install pin cmeel-eigen`).
mkdir -p "$out"
python3 scripts/pinocchio_derivatives.py --save-models "$out"
prefix="$(python3 -c 'import pinocchio, pathlib; print(pathlib.Path(pinocchio.__file__).parents[4])')"
extra_libs=()
pinocchio_cxx() {
    local source=$1 output=$2
    shift 2
    g++ "$@" -DNDEBUG -std=c++17 \
        -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
        -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
        -I"$prefix/include" -I"$prefix/include/eigen3" "$source" -o "$output" \
        -L"$prefix/lib" -lpinocchio_default "${extra_libs[@]}" -lboost_serialization \
        -lboost_filesystem -Wl,-rpath,"$prefix/lib"
}
