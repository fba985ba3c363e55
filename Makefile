# fretwear: `make demo` and `make test` each create or update .venv and run.
PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed

.PHONY: demo test browser bench lint clean

$(STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[dev]'
	touch $(STAMP)

demo: $(STAMP)
	$(VENV)/bin/fretwear run examples/tube_bav.toml -o build/demo/wear_table.csv --plot build/demo

# The HTML report's test opens the page in a headless chromium: installed here when missing and
# apt-get can (root, Debian's registry reachable, as in CI); otherwise that test is skipped.
# The second line runs the tests marked numeric again with numpy's SIMD dispatch targets and
# numba's CPU turned down (tests/reduced_simd.py): a result that holds only on this processor's
# code paths fails here, not on the next machine.
test: $(STAMP) browser
	$(PY) -m pytest -n 2 -q
	$(PY) tests/reduced_simd.py -n 2 -q

browser:
	@if command -v chromium >/dev/null 2>&1 || command -v chromium-browser >/dev/null 2>&1; \
	then :; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	  echo "make: installing chromium for the report's browser test"; \
	  DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium >/dev/null 2>&1 \
	  || { apt-get update -q >/dev/null 2>&1 \
	       && DEBIAN_FRONTEND=noninteractive apt-get install -y -q chromium >/dev/null 2>&1; } \
	  || echo "make: chromium could not be installed; the report's browser test will skip"; \
	else echo "make: no chromium and no root apt-get; the report's browser test will skip"; fi

bench: $(STAMP)
	$(PY) benchmarks/bench_power.py
	$(PY) benchmarks/bench_dynamics.py
	$(PY) benchmarks/bench_table.py

lint: $(STAMP)
	$(VENV)/bin/ruff check src tests benchmarks

clean:
	rm -rf $(VENV) build .pytest_cache
