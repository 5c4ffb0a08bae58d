# The README's commands. Each sets itself up first (idempotent; see scripts/setup.sh).
VENV := .venv
PY := $(VENV)/bin/python
SOURCES := $(shell find src python -type f \( -name '*.cpp' -o -name '*.h' -o -name '*.py' -o -name 'CMakeLists.txt' \)) pyproject.toml CMakeLists.txt

.PHONY: setup install demo test test-fast lint bench clean

setup: $(VENV)/.setup-done
$(VENV)/.setup-done: scripts/setup.sh
	bash scripts/setup.sh
	touch $@

# Rebuilds only when a source changed; build/ keeps CMake's incremental state.
install: $(VENV)/.installed
$(VENV)/.installed: $(VENV)/.setup-done $(SOURCES)
	$(PY) -m pip install -q --disable-pip-version-check --no-build-isolation .
	touch $@

demo: install
	$(PY) -m dualight demo --out out

test: install
	$(VENV)/bin/ruff check python tests benchmarks
	$(PY) -m pytest -q

test-fast: install
	$(PY) -m pytest -q -m "not slow and not mitsuba"

bench: install
	$(PY) benchmarks/bench_path.py

clean:
	rm -rf build out $(VENV)/.installed
