# The README's commands. Each sets itself up first (idempotent; see scripts/setup.sh).
VENV := .venv
PY := $(VENV)/bin/python
# Everything the wheel holds: code, and the package's data (references, scenes' textures).
SOURCES := $(shell find src python tests/hooks -type f \( -name '*.cpp' -o -name '*.h' -o -name '*.py' -o -name '*.pyi' -o -name 'CMakeLists.txt' -o -path 'python/dualight/data/*' \)) pyproject.toml CMakeLists.txt

.PHONY: setup install demo test test-long test-fast test-sanitize fuzz cpp-test bench bench-quick bench-topics stubs clean

setup: $(VENV)/.setup-done
$(VENV)/.setup-done: scripts/setup.sh
	bash scripts/setup.sh
	touch $@

# Rebuilds only when a source changed; build/<wheel tag> keeps CMake's incremental state (a plain
# `pip install .` builds in a temporary folder instead). With the test hooks module
# dualight._testing (tests/hooks), which a plain `pip install .` leaves out.
install: $(VENV)/.installed
$(VENV)/.installed: $(VENV)/.setup-done $(SOURCES)
	$(PY) -m pip install -q --disable-pip-version-check --no-build-isolation \
	  --config-settings=build-dir=build/{wheel_tag} \
	  --config-settings=cmake.define.DUALIGHT_TESTING=ON .
	touch $@

demo: install
	$(PY) -m dualight demo --out out

# pytest runs last: its summary is the closing line CI reads.
test: install cpp-test
	$(VENV)/bin/ruff check python tests benchmarks notebooks
	$(PY) -m pytest -q

# C++ unit tests (tests/cpp) through ctest, in their own incremental build folder.
cpp-test: setup
	cmake -S . -B build/cpp-tests -DDUALIGHT_PYTHON=OFF -DBUILD_TESTING=ON -DCMAKE_BUILD_TYPE=Release >/dev/null
	cmake --build build/cpp-tests -j 2
	ctest --test-dir build/cpp-tests --output-on-failure

# The checks left out of make test for its time (marker `long`: more estimators on the
# material scenes against their Mitsuba references). About 11 minutes.
test-long: install
	$(PY) -m pytest -q --long -m long

test-fast: install
	$(PY) -m pytest -q -m "not slow and not mitsuba and not fuzz"

# The C++ unit tests and a fast pytest subset under AddressSanitizer and UBSan, built in
# build/sanitize (its own package folder; .venv keeps the normal build). A few minutes.
test-sanitize: setup
	bash scripts/test_sanitize.sh

# Each atheris fuzz target for FUZZ_SECONDS (default 300), corpus kept in build/fuzz/<target>;
# crashing inputs land in build/fuzz/ (add them to tests/fuzz/regressions/<target>/).
FUZZ_SECONDS ?= 300
fuzz: install
	@for t in scene loaders tasks; do \
	  mkdir -p build/fuzz/$$t; echo "fuzz_$$t: $(FUZZ_SECONDS) s, log in build/fuzz/$$t.log"; \
	  $(PY) tests/fuzz/fuzz_$$t.py -max_total_time=$(FUZZ_SECONDS) -rss_limit_mb=4096 -timeout=60 \
	    -print_final_stats=1 -artifact_prefix=build/fuzz/ build/fuzz/$$t >build/fuzz/$$t.log 2>&1; \
	  status=$$?; grep -E "^(Done|stat::average_exec_per_sec|fuzz_)" build/fuzz/$$t.log; \
	  if [ $$status -ne 0 ]; then tail -40 build/fuzz/$$t.log; exit 1; fi; \
	done

# Error against run time of every method on the scene set (out/bench; --quick: under 5 min).
bench: install
	$(PY) -m dualight bench

bench-quick: install
	$(PY) -m dualight bench --quick

# The per-topic benchmarks (benchmarks/, results in benchmarks/results).
bench-topics: install
	$(PY) benchmarks/bench_path.py
	$(PY) benchmarks/bench_radiosity.py
	$(PY) benchmarks/bench_hierarchical.py
	$(PY) benchmarks/bench_bdpt.py
	$(PY) benchmarks/bench_bdpt_rr.py
	$(PY) benchmarks/bench_mlt.py

# Regenerates python/dualight/_core.pyi from the built extension (commit the result; the
# tests check that it names everything _core exports).
stubs: install
	$(PY) -m pybind11_stubgen dualight._core -o build/stubs \
	  --enum-class-locations "MisHeuristic|RefinementOracle|SamplerType|Strategies|TransportMode|BsdfKind:dualight._core"
	cp build/stubs/dualight/_core.pyi python/dualight/_core.pyi

clean:
	rm -rf build out $(VENV)/.installed
