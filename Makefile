# Signorini contact solver.  `make run` solves Example 1, `make test` runs the tests (README.md).
PETSC_DIR ?= /usr/lib/petsc
PETSC_VARIABLES := $(wildcard $(PETSC_DIR)/lib/petsc/conf/variables)
ifneq ($(PETSC_VARIABLES),)
include $(PETSC_VARIABLES)
endif
PYTHON  ?= /usr/bin/python3
MPIEXEC ?= mpiexec
NP      ?= 1
export OMPI_ALLOW_RUN_AS_ROOT = 1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM = 1
export OMPI_MCA_rmaps_base_oversubscribe = 1

CC     := mpicc
CFLAGS ?= -O2 -g
CFLAGS += -Wall -Wextra -Wno-unused-parameter -MMD -MP $(PETSC_CC_INCLUDES)
LDLIBS  = $(PETSC_WITH_EXTERNAL_LIB) -lm

SRC    := $(wildcard src/*.c)
LIBOBJ := $(patsubst src/%.c,build/%.o,$(filter-out src/main.c,$(SRC)))

# Example 1 with exact solves and the inexact path-following controller (options files compose; later ones override)
EX1 = -options_file options/ex1.opts -options_file options/solver/mumps.opts -options_file options/cont/ipf.opts
TARGETS = all run test table1 reproduce figures

.PHONY: $(TARGETS) deps clean

ifeq ($(PETSC_VARIABLES),)
# PETSc is missing: install the Debian packages when root, otherwise say how.
$(TARGETS):
	@scripts/install-deps.sh
	@$(MAKE) --no-print-directory $@
else
all: bin/signorini bin/unit_tests

run: all
	@scripts/install-deps.sh
	@mkdir -p results
	$(MPIEXEC) -n $(NP) bin/signorini $(EX1) -output_file results/ex1.h5 -summary_file results/ex1.json -history_file results/ex1.csv
	$(PYTHON) scripts/plot_mesh.py results/ex1.h5 results/ex1.png
	@echo "results: results/ex1.h5 (open results/ex1.xmf in ParaView), results/ex1.json, results/ex1.csv, results/ex1.png"

test: all
	@scripts/install-deps.sh
	$(PYTHON) tests/harness.py tests/*.ini

# The paper's tables side by side with ours (results/*.md) and its figures (results/fig*.png)
table1: all
	$(PYTHON) scripts/reproduce.py --only table1 --out results/table1.md
reproduce: all
	$(PYTHON) scripts/reproduce.py
figures: all
	$(PYTHON) scripts/figures.py --only ex1
endif

deps:
	scripts/install-deps.sh

build/%.o: src/%.c | build
	$(CC) $(CFLAGS) -c $< -o $@
build/unit_tests.o: tests/unit_tests.c | build
	$(CC) $(CFLAGS) -Isrc -c $< -o $@
bin/signorini: build/main.o $(LIBOBJ) | bin
	$(CC) -o $@ $^ $(LDLIBS)
bin/unit_tests: build/unit_tests.o $(LIBOBJ) | bin
	$(CC) -o $@ $^ $(LDLIBS)
build bin:
	mkdir -p $@

clean:
	rm -rf build bin tests/output

-include $(wildcard build/*.d)
