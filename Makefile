# symctl: `make paper` and `make test` do all the set-up themselves (a local .venv).
PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
OUT ?= out/paper

.PHONY: all paper examples test lint format bench clean

all: test

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[dev]"
	touch $(STAMP)

paper: $(STAMP)
	$(BIN)/symctl paper --out $(OUT)

EXAMPLES := $(wildcard examples/*.toml)

examples: $(STAMP)
	@for f in $(EXAMPLES); do \
		name=$$(basename $$f .toml); \
		echo "== $$f -> out/$$name"; \
		$(BIN)/symctl derive $$f --out out/$$name || exit $$?; \
	done

test: $(STAMP)
	$(BIN)/python -m pytest -n 2 -q

lint: $(STAMP)
	$(BIN)/ruff check symctl tests benchmarks conftest.py
	$(BIN)/ruff format --check symctl tests benchmarks conftest.py

format: $(STAMP)
	$(BIN)/ruff format symctl tests benchmarks conftest.py
	$(BIN)/ruff check --fix symctl tests benchmarks conftest.py

bench: $(STAMP)
	$(BIN)/python -m pip install --quiet -e ".[bench]"
	$(BIN)/python benchmarks/core.py
	$(BIN)/python benchmarks/checker.py
	$(BIN)/python benchmarks/compatibility.py
	$(BIN)/python benchmarks/simulate.py
	$(BIN)/python benchmarks/paper.py
	$(BIN)/python benchmarks/scaling.py
	$(BIN)/python benchmarks/mimo.py
	$(BIN)/python benchmarks/atlas.py
	$(BIN)/python benchmarks/examples.py
	$(BIN)/python benchmarks/dale.py --workers 2
	$(BIN)/python benchmarks/fit.py

clean:
	rm -rf $(VENV) out .pytest_cache .hypothesis
