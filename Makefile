# symctl: `make paper`, `make test` and `make docs` do all the set-up themselves (a local .venv).
PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
DOCS_STAMP := $(VENV)/.installed-docs
SPIKING_STAMP := $(VENV)/.installed-spiking
OUT ?= out/paper
DOCS_OUT := docs/_build/html
PY_FILES := symctl tests benchmarks conftest.py docs/conf.py docs/_ext docs/run_notebooks.py

.PHONY: all paper examples test test-all lint format bench clean docs docs-check notebooks

all: test

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[dev]"
	touch $(STAMP)

# the documentation site's tools (Sphinx, myst-nb, numpydoc, MathJax, Playwright): the docs extra
$(DOCS_STAMP): $(STAMP)
	$(BIN)/python -m pip install --quiet -e ".[dev,docs]"
	touch $(DOCS_STAMP)

# the spiking extra (nengo, NEST): its tests skip without it in `make test`, run in `make test-all`
$(SPIKING_STAMP): $(STAMP)
	$(BIN)/python -m pip install --quiet -e ".[dev,spiking]"
	touch $(SPIKING_STAMP)

paper: $(STAMP)
	$(BIN)/symctl paper --out $(OUT)

EXAMPLES := $(wildcard examples/*.toml)

examples: $(STAMP)
	@for f in $(EXAMPLES); do \
		name=$$(basename $$f .toml); \
		echo "== $$f -> out/$$name"; \
		$(BIN)/symctl derive $$f --out out/$$name || exit $$?; \
	done

# the fast tier: unit, property (10 examples each) and doctests on small objects, one end-to-end
# run of each CLI command
test: $(STAMP)
	SYMCTL_EXAMPLES=$${SYMCTL_EXAMPLES:-10} $(BIN)/python -m pytest -n 2 -q -m "not slow and not docs"

# both tiers (what CI runs): adds every example end to end, the notebooks, PDF compiles, dask
# clusters, the console script's subprocess runs, the spiking extra's exports (nengo, NEST); 40
# examples per property; the 25 slowest listed
test-all: $(SPIKING_STAMP)
	SYMCTL_REQUIRE_SPIKING=1 $(BIN)/python -m pytest -n 2 -q --durations=25

lint: $(STAMP)
	$(BIN)/ruff check $(PY_FILES)
	$(BIN)/ruff format --check $(PY_FILES)

format: $(STAMP)
	$(BIN)/ruff format $(PY_FILES)
	$(BIN)/ruff check --fix $(PY_FILES)

# the documentation site, into docs/_build/html: the notebooks executed and `symctl paper` run
# while it builds; every warning is an error; -E reads every page again, so none is hidden
docs: $(DOCS_STAMP)
	$(BIN)/sphinx-build -b html -W --keep-going -E -j 2 -q docs $(DOCS_OUT)
	@echo "docs: $(DOCS_OUT)/index.html"

# the built site in headless Chromium (Debian's /usr/bin/chromium): math, images, links, no
# request off 127.0.0.1; screenshots in out/docs-check/
docs-check: $(DOCS_STAMP)
	$(BIN)/python -m pytest tests/docs -m docs -p no:xdist -q

# run every notebook and store it with its outputs (commit the result)
notebooks: $(STAMP)
	$(BIN)/python docs/run_notebooks.py

# every benchmark against its baseline, in one run; writes docs/benchmarks.md
bench: $(SPIKING_STAMP)
	$(BIN)/python -m pip install --quiet -e ".[bench]"
	$(BIN)/python benchmarks/run_all.py --out docs/benchmarks.md

clean:
	rm -rf $(VENV) out .pytest_cache .hypothesis docs/_build docs/generated
