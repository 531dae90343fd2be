# Signorini contact solver: build, run, test.  See README.md.
PETSC_DIR ?= /usr/lib/petsc
PETSC_VARIABLES := $(wildcard $(PETSC_DIR)/lib/petsc/conf/variables)
ifneq ($(PETSC_VARIABLES),)
include $(PETSC_VARIABLES)
endif
PYTHON ?= /usr/bin/python3
MPIEXEC ?= mpiexec
export OMPI_ALLOW_RUN_AS_ROOT = 1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM = 1
export OMPI_MCA_rmaps_base_oversubscribe = 1

CC := mpicc
CFLAGS ?= -O2 -g
CFLAGS += -Wall -Wextra -Wno-unused-parameter -MMD -MP $(PETSC_CC_INCLUDES)
LDLIBS = $(PETSC_WITH_EXTERNAL_LIB) -lm

SRC := $(wildcard src/*.c)
LIBOBJ := $(patsubst src/%.c,build/%.o,$(filter-out src/main.c,$(SRC)))

.PHONY: all deps check-deps run test clean
all: check-deps bin/signorini

check-deps:
	@if [ -z "$(PETSC_VARIABLES)" ]; then \
	  if [ "$$(id -u)" = 0 ]; then $(MAKE) --no-print-directory deps; \
	  else echo "PETSc is missing: run as root  sudo scripts/install-deps.sh"; exit 1; fi; \
	  $(MAKE) --no-print-directory all; \
	fi

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
	rm -rf build bin

-include $(wildcard build/*.d)
