#!/usr/bin/env bash
# `make test-sanitize`: the C++ core, its unit tests and the Python extension built with
# AddressSanitizer and UndefinedBehaviorSanitizer (DUALIGHT_SANITIZE=ON) in build/sanitize, and
# the fast tests run under them. The instrumented package goes to build/sanitize/site (put first
# on PYTHONPATH), never into .venv: the normal build stays as it is. Incremental and idempotent:
# CMake rebuilds only what changed.
#
# CPython is not instrumented, so the ASan runtime is preloaded and leak detection is off (the
# interpreter "leaks" by design). Any ASan or UBSan report aborts the run with its stack.
set -euo pipefail
cd "$(dirname "$0")/.."

PY=.venv/bin/python
BUILD=build/sanitize
SITE=$BUILD/site
# A few minutes under the sanitizers: the fast tests of the areas that reach the C++ core (scene
# building, image I/O, BSDFs, samplers, each estimator, form factors and the solvers). The
# statistical MLT tests (100000-sample bootstraps at 64 x 64) take too long under ASan: one
# deterministic MLT render stands in for them, and the chain split (exact sums, chain parts
# through bytes) runs in process.
PYTEST_FILES=${PYTEST_FILES:-"tests/test_scene.py tests/test_image.py tests/test_materials.py \
tests/test_sampler.py tests/test_path_tracer.py tests/test_bdpt.py tests/test_form_factors.py \
tests/test_radiosity.py tests/test_hierarchical.py tests/test_skipping.py \
tests/test_mlt_path_space.py::test_mlt_is_deterministic_and_reports_each_mutation \
tests/test_mlt_mutations.py::test_single_mutation_hook_rejects_unknown_names \
tests/test_executor.py::test_any_split_of_the_chains_gives_the_same_image tests/test_task_data.py"}
# Then the task-data fuzz target (chain start-ups, chain parts, blocks of samples from other
# processes) under the sanitizers for this long. With ASan's runtime preloaded, libFuzzer gets
# no coverage (atheris takes its coverage symbols from libasan, see atheris' using_sanitizers.md)
# and would drop every seed as uninteresting, mutating a 1-byte input blindly (inputs of at most
# a few hundred bytes, never a valid layout): -keep_seed=1 keeps the seeds' real layouts as the
# starting points of its mutations. `make fuzz`, without the sanitizers, has the coverage.
FUZZ_SECONDS=${SANITIZE_FUZZ_SECONDS:-120}

start=$(date +%s)
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDUALIGHT_SANITIZE=ON \
  -DCMAKE_INTERPROCEDURAL_OPTIMIZATION=OFF -DBUILD_TESTING=ON -DDUALIGHT_PYTHON=ON -DDUALIGHT_TESTING=ON \
  -DPython_EXECUTABLE="$PWD/$PY" -Dpybind11_DIR="$("$PY" -m pybind11 --cmakedir)" >/dev/null
cmake --build "$BUILD" -j 2

# The package from the source tree plus the instrumented extension and test hooks module.
rm -rf "$SITE/dualight"
mkdir -p "$SITE/dualight"
cp -r python/dualight/. "$SITE/dualight/"
cp "$BUILD"/src/_core*.so "$BUILD"/tests/hooks/_testing*.so "$SITE/dualight/"

export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:strict_init_order=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
built=$(date +%s)

echo "test-sanitize: C++ unit tests (ctest)"
ctest --test-dir "$BUILD" --output-on-failure

echo "test-sanitize: pytest (fast subset) under ASan and UBSan"
LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)" \
  PYTHONPATH="$PWD/$SITE" "$PY" -m pytest -q -p no:cacheprovider \
  --durations=5 -m "not slow and not mitsuba and not fuzz" $PYTEST_FILES "$@"
echo "test-sanitize: fuzz_tasks for $FUZZ_SECONDS s under ASan and UBSan"
mkdir -p "$BUILD/fuzz/tasks"
LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)" \
  PYTHONPATH="$PWD/$SITE" "$PY" tests/fuzz/fuzz_tasks.py -max_total_time="$FUZZ_SECONDS" -timeout=60 \
  -rss_limit_mb=8192 -keep_seed=1 -print_final_stats=1 -artifact_prefix="$BUILD/fuzz/" "$BUILD/fuzz/tasks" \
  >"$BUILD/fuzz/tasks.log" 2>&1 || { tail -40 "$BUILD/fuzz/tasks.log"; exit 1; }
grep -E "^Done" "$BUILD/fuzz/tasks.log"
python_dualight=$(PYTHONPATH="$PWD/$SITE" LD_PRELOAD="$(gcc -print-file-name=libasan.so)" \
  "$PY" -c "import dualight._core as c; print(c.__file__)")
case "$python_dualight" in
  "$PWD/$SITE"/*) ;;
  *) echo "test-sanitize: the tests did not import the instrumented build: $python_dualight" >&2
     exit 1 ;;
esac
end=$(date +%s)
echo "test-sanitize: clean (build $((built - start)) s, tests $((end - built)) s)"
