# Signorini contact solver.  `make` builds the library (lib/) and the driver (bin/), `make run` solves Example 1,
# `make test` runs the tests, `make install PREFIX=...` installs the library (README.md).
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
# one BLAS thread per MPI rank: the ranks already use the cores
export OPENBLAS_NUM_THREADS = 1

CC     := mpicc
AR     ?= ar
CFLAGS ?= -O2 -g
# include/: the public header (installed); src/: the library's private headers
CFLAGS += -Wall -Wextra -Wno-unused-parameter -MMD -MP -Iinclude -Isrc $(PETSC_CC_INCLUDES)
LDLIBS  = $(PETSC_WITH_EXTERNAL_LIB) -lgmsh -lm

# The library: VERSION names the release (signorini.pc, the file name of the shared library); SOVERSION is the ABI
# in the soname, libsignorini.so.$(SOVERSION): raise it whenever a program built against include/signorini.h would
# break with the new library (a function's arguments, SgKKT's fields, a removed function), not for additions.
VERSION   = 0.1.0
SOVERSION = 0
LIBA      = lib/libsignorini.a
LIBSO     = lib/libsignorini.so
LIBSOV    = $(LIBSO).$(VERSION)
LIBSONAME = libsignorini.so.$(SOVERSION)

# make install PREFIX=... (DESTDIR= for a staged install); the pkg-config file records $(PREFIX)
PREFIX  ?= /usr/local
ABSPREFIX = $(abspath $(PREFIX))
INSTALL ?= install
# signorini.pc requires the PETSc minor release the library was built with (PETSc's ABI changes with each)
PETSC_VERSION_H := $(firstword $(wildcard $(PETSC_DIR)/include/petscversion.h))
ifneq ($(PETSC_VERSION_H),)
PETSC_MAJOR := $(shell sed -n 's/^.define PETSC_VERSION_MAJOR *//p' $(PETSC_VERSION_H))
PETSC_MINOR := $(shell sed -n 's/^.define PETSC_VERSION_MINOR *//p' $(PETSC_VERSION_H))
PETSC_NEXT_MINOR := $(shell echo $$(( $(PETSC_MINOR) + 1 )))
endif

MESHES  = meshes/beam.msh meshes/ex2.msh meshes/ex2_coarse.msh meshes/hertz_s1.msh meshes/hertz_s2.msh meshes/hertz_s4.msh meshes/cattaneo_s1.msh meshes/cattaneo_s2.msh meshes/cattaneo_s4.msh meshes/punch_block.msh \
          $(CURVED_MESHES) $(TWOBODY_MESHES) $(MATERIAL_MESHES)
# Curved and tilted bodies (tests/verification/curved.ini): the coarse meshes its tests read; cv_*_rNN are rigidly turned copies of
# a mesh (tests/rotate_msh.py: the same elements, nodes turned by NN degrees; see the rules below)
CURVED_MESHES = meshes/cv_tilt2d_s1.msh meshes/cv_tilt3d_s1.msh meshes/cv_hemisphere_s1.msh meshes/cv_hemisphere_s2.msh \
          meshes/cv_halfdisc_s1.msh meshes/cv_halfdisc_s2.msh meshes/cv_halfdisc_s4.msh meshes/cv_halfdisc_s32.msh meshes/cv_halfdisc_full.msh \
          meshes/cv_halfdisc_full_r30.msh meshes/cv_halfdisc_full_r135.msh meshes/cv_block2d.msh meshes/cv_block2d_r20.msh \
          meshes/ex2_s0.3.msh meshes/cv_ex2_s0.3_r30.msh meshes/cv_ex2_s0.3_r75.msh meshes/ex2_s1.msh meshes/cv_ex2_s1_r30.msh meshes/cv_ex2_s1_r75.msh \
          meshes/cv_ex2_s1_r15.msh meshes/cv_ex2_s1_r45.msh meshes/cv_ex2_coarse_r30.msh meshes/cv_ex2_coarse_r75.msh
# Two bodies in one mesh (tests/unit/kernels.ini, tests/*/twobody.ini, tests/*/twobody_fields.ini, options/twobody_hertz.opts,
# options/twobody_sphere.opts); _r25: turned by 25 degrees
TWOBODY_MESHES = meshes/tb_blocks2d.msh meshes/tb_blocks2d_r25.msh meshes/tb_blocks3d.msh meshes/tb_stack2d.msh meshes/tb_stack3d.msh \
          meshes/tb_stack2d_match.msh meshes/tb_far2d.msh meshes/tb_overlap2d.msh meshes/tb_far3d.msh meshes/tb_overlap3d.msh \
          meshes/tb_cylinders2d_s1.msh meshes/tb_cylinders2d_s2.msh meshes/tb_cylinders2d_s4.msh \
          meshes/tbf_stack2d.msh meshes/tbf_stack3d.msh meshes/tbf_cattaneo_s1.msh meshes/tbf_cattaneo_s2.msh meshes/tbf_cattaneo_s4.msh \
          meshes/tb_sphere_s1.msh meshes/tb_sphere_s2.msh meshes/tb_mirror2d.msh meshes/tb_mirror3d.msh
# Several materials and bodies in one mesh (tests/*/materials.ini)
MATERIAL_MESHES = meshes/mat_bar2d.msh meshes/mat_two2d.msh meshes/mat_layers3d.msh meshes/mat_two3d.msh
# The user guide's own-mesh example of a body resting on its support (options/newuser_holeplate.opts)
MESHES += meshes/newuser_holeplate.msh
# Example 2's second coarse mesh (bench/perf_nested.py --default ex2_coarse2:3): 9,432 unknowns, about 4e6 with -dm_refine 3
MESHES += meshes/ex2_coarse2.msh
SRC    := $(wildcard src/*/*.c)
LIBOBJ := $(patsubst src/%.c,build/%.o,$(SRC))

# Example 1 with exact solves and the inexact path-following controller (options files compose; later ones override)
EX1 = -options_file options/ex1.opts -options_file options/solver/mumps.opts -options_file options/cont/ipf.opts
TARGETS = all run test check-memory fuzz table1 reproduce figures meshes bench install

.PHONY: $(TARGETS) uninstall deps clean print-cflags format format-check

ifeq ($(PETSC_VARIABLES),)
# PETSc is missing: install the Debian packages when root, otherwise say how.
$(TARGETS):
	@scripts/install-deps.sh
	@$(MAKE) --no-print-directory $@
else
all: $(LIBA) $(LIBSO) bin/signorini bin/unit_tests bin/misuse_tests $(MESHES)

run: all
	@scripts/install-deps.sh
	@mkdir -p results
	$(MPIEXEC) -n $(NP) bin/signorini $(EX1) -output_file results/ex1.h5 -summary_file results/ex1.json -history_file results/ex1.csv
	$(PYTHON) scripts/plot_mesh.py results/ex1.h5 results/ex1.png
	@echo "results: results/ex1.h5 (open results/ex1.xmf in ParaView), results/ex1.json, results/ex1.csv, results/ex1.png"

# GROUP=unit (verification, regression, features, input, parallel) runs one group of tests/ (and the tests they depend on)
TEST_DIR = tests$(if $(GROUP),/$(GROUP))
test: all
	@scripts/install-deps.sh
	$(PYTHON) tests/harness.py $(TEST_DIR)

# Meshes generated by gmsh from meshes/*.geo (Debian's gmsh 4.8: the same mesh on every machine of this kind)
meshes:
	rm -f $(MESHES)
	$(MAKE) --no-print-directory $(MESHES)

# The tests tagged `memcheck = yes` (tests/harness.py's docstring says which to tag) under valgrind memcheck: no
# errors, no definite leaks (tests/valgrind.supp holds OpenMPI's own start-up leaks); about 15 minutes on 2 cores.
check-memory: all
	$(PYTHON) tests/harness.py --valgrind $(TEST_DIR)

# Randomized robustness test, the larger set (make test runs 200 cases of it): FUZZ_SEED, FUZZ_COUNT, FUZZ_TIME override
FUZZ_SEED  ?= 1
FUZZ_COUNT ?= 2000
FUZZ_TIME  ?= 1800
fuzz: all
	$(PYTHON) tests/fuzz.py --count $(FUZZ_COUNT) --seed $(FUZZ_SEED) --time-limit $(FUZZ_TIME)

# The paper's tables side by side with ours (results/*.md), its figures (results/fig*.png) and the friction pictures
table1: all
	$(PYTHON) scripts/reproduce.py --only table1 --out results/table1.md
reproduce: all
	$(PYTHON) scripts/reproduce.py
figures: all
	$(PYTHON) scripts/figures.py --only ex1,ex2,loadsteps,punch,friction,cattaneo,twobody
# Benchmarks (not tests): bench/results.md and bench/results.json; two to three and a half hours on 2 cores
bench: all meshes/ex2_s2.msh meshes/ex2_s4.2.msh
	$(PYTHON) scripts/bench.py $(BENCH_FLAGS)

# The public header, both libraries, signorini.pc (from signorini.pc.in: the prefix, PETSc's version and libraries)
# and the driver. The shared library's links as ldconfig would make them, so no ldconfig run is needed.
install: $(LIBA) $(LIBSO) bin/signorini
	$(INSTALL) -d $(DESTDIR)$(ABSPREFIX)/include $(DESTDIR)$(ABSPREFIX)/lib/pkgconfig $(DESTDIR)$(ABSPREFIX)/bin
	$(INSTALL) -m 644 include/signorini.h $(DESTDIR)$(ABSPREFIX)/include/
	$(INSTALL) -m 644 $(LIBA) $(DESTDIR)$(ABSPREFIX)/lib/
	$(INSTALL) -m 755 $(LIBSOV) $(DESTDIR)$(ABSPREFIX)/lib/
	ln -sf $(notdir $(LIBSOV)) $(DESTDIR)$(ABSPREFIX)/lib/$(LIBSONAME)
	ln -sf $(LIBSONAME) $(DESTDIR)$(ABSPREFIX)/lib/libsignorini.so
	sed -e 's|@PREFIX@|$(ABSPREFIX)|g' -e 's|@VERSION@|$(VERSION)|g' -e 's|@CC@|$(CC)|g' \
	    -e 's|@PETSC_MAJOR@|$(PETSC_MAJOR)|g' -e 's|@PETSC_MINOR@|$(PETSC_MINOR)|g' \
	    -e 's|@PETSC_NEXT_MINOR@|$(PETSC_NEXT_MINOR)|g' -e 's|@PETSC_EXTERNAL_LIBS@|$(PETSC_EXTERNAL_LIB_BASIC)|g' \
	    signorini.pc.in > $(DESTDIR)$(ABSPREFIX)/lib/pkgconfig/signorini.pc
	$(INSTALL) -m 755 bin/signorini $(DESTDIR)$(ABSPREFIX)/bin/
endif

deps:
	scripts/install-deps.sh

# The C sources in the style .clang-format describes (clang-format 14: apt-get install clang-format). format-check
# names the files whose lines differ and how many, and fails if any do; format rewrites them in place.
FORMAT_FILES = $(sort $(wildcard include/*.h src/*.h src/*/*.h src/*/*.c app/*.c tests/*.c examples/*.c))
CLANG_FORMAT ?= clang-format
format:
	@command -v $(CLANG_FORMAT) > /dev/null || { echo "$(CLANG_FORMAT) not found: apt-get install clang-format"; exit 1; }
	$(CLANG_FORMAT) -i --style=file $(FORMAT_FILES)
format-check:
	@command -v $(CLANG_FORMAT) > /dev/null || { echo "$(CLANG_FORMAT) not found: apt-get install clang-format"; exit 1; }
	@n=0; for f in $(FORMAT_FILES); do \
	  c=$$($(CLANG_FORMAT) --style=file $$f | diff $$f - | grep -c '^<'); \
	  if [ "$$c" != 0 ]; then echo "$$f: $$c lines"; n=$$((n + c)); fi; \
	done; echo "$$n lines differ from .clang-format's style (make format rewrites them)"; [ "$$n" = 0 ]

# what make install put under PREFIX (needs no PETSc)
uninstall:
	rm -f $(DESTDIR)$(ABSPREFIX)/include/signorini.h $(DESTDIR)$(ABSPREFIX)/lib/pkgconfig/signorini.pc \
	      $(DESTDIR)$(ABSPREFIX)/lib/libsignorini.a $(DESTDIR)$(ABSPREFIX)/lib/libsignorini.so \
	      $(DESTDIR)$(ABSPREFIX)/lib/$(LIBSONAME) $(DESTDIR)$(ABSPREFIX)/lib/$(notdir $(LIBSOV)) \
	      $(DESTDIR)$(ABSPREFIX)/bin/signorini

meshes/beam.msh: meshes/beam.geo
	gmsh -2 $< -o $@ > /dev/null
meshes/ex2.msh: meshes/ex2.geo
	gmsh -3 $< -o $@ > /dev/null
meshes/ex2_coarse.msh: meshes/ex2.geo
	gmsh -3 -setnumber scale 0.5 $< -o $@ > /dev/null
meshes/ex2_coarse2.msh: meshes/ex2.geo
	gmsh -3 -setnumber scale 0.8 $< -o $@ > /dev/null
meshes/hertz_s%.msh: meshes/hertz.geo
	gmsh -3 -setnumber scale $* $< -o $@ > /dev/null
meshes/cattaneo_s%.msh: meshes/cattaneo.geo
	gmsh -2 -setnumber scale $* $< -o $@ > /dev/null
meshes/ex2_s%.msh: meshes/ex2.geo
	gmsh -3 -setnumber scale $* $< -o $@ > /dev/null
meshes/punch_block.msh: meshes/punch_block.geo
	gmsh -3 $< -o $@ > /dev/null
meshes/cv_tilt2d_s%.msh: meshes/cv_tilt2d.geo
	gmsh -2 -setnumber scale $* $< -o $@ > /dev/null
meshes/cv_tilt3d_s%.msh: meshes/cv_tilt3d.geo
	gmsh -3 -setnumber scale $* $< -o $@ > /dev/null
meshes/cv_hemisphere_s%.msh: meshes/cv_hemisphere.geo
	gmsh -3 -setnumber scale $* $< -o $@ > /dev/null
meshes/cv_halfdisc_s%.msh: meshes/cv_halfdisc.geo
	gmsh -2 -setnumber scale $* $< -o $@ > /dev/null
meshes/cv_halfdisc_full.msh: meshes/cv_halfdisc.geo
	gmsh -2 -setnumber full 1 $< -o $@ > /dev/null
meshes/mat_%2d.msh: meshes/mat_%2d.geo
	gmsh -2 $< -o $@ > /dev/null
meshes/mat_%3d.msh: meshes/mat_%3d.geo
	gmsh -3 $< -o $@ > /dev/null
meshes/cv_block2d.msh: meshes/cv_tilt2d.geo
	gmsh -2 -setnumber angle 0 $< -o $@ > /dev/null
meshes/newuser_holeplate.msh: meshes/newuser_holeplate.geo
	gmsh -3 $< -o $@ > /dev/null
meshes/tb_blocks2d.msh: meshes/tb_blocks2d.geo
	gmsh -2 $< -o $@ > /dev/null
meshes/tb_blocks3d.msh: meshes/tb_blocks3d.geo
	gmsh -3 $< -o $@ > /dev/null
meshes/tb_stack2d.msh: meshes/tb_stack2d.geo
	gmsh -2 $< -o $@ > /dev/null
meshes/tb_stack3d.msh: meshes/tb_stack3d.geo
	gmsh -3 $< -o $@ > /dev/null
# the patch test's blocks 1.5 apart (farther than the pairing distance: a warning, solved without contact) and
# overlapping by 0.3 at the start (an error)
meshes/tb_stack2d_match.msh: meshes/tb_stack2d.geo
	gmsh -2 -setnumber h2 0.1 $< -o $@ > /dev/null
meshes/tb_far2d.msh: meshes/tb_stack2d.geo
	gmsh -2 -setnumber g0 1.5 $< -o $@ > /dev/null
meshes/tb_overlap2d.msh: meshes/tb_stack2d.geo
	gmsh -2 -setnumber g0 -0.3 $< -o $@ > /dev/null
meshes/tb_far3d.msh: meshes/tb_stack3d.geo
	gmsh -3 -setnumber g0 1.5 $< -o $@ > /dev/null
meshes/tb_overlap3d.msh: meshes/tb_stack3d.geo
	gmsh -3 -setnumber g0 -0.3 $< -o $@ > /dev/null
meshes/tb_cylinders2d_s%.msh: meshes/tb_cylinders2d.geo
	gmsh -2 -setnumber scale $* $< -o $@ > /dev/null
meshes/tbf_stack2d.msh: meshes/tbf_stack2d.geo
	gmsh -2 $< -o $@ > /dev/null
meshes/tbf_stack3d.msh: meshes/tbf_stack3d.geo
	gmsh -3 $< -o $@ > /dev/null
meshes/tbf_cattaneo_s%.msh: meshes/tbf_cattaneo.geo
	gmsh -2 -setnumber scale $* $< -o $@ > /dev/null
meshes/tb_sphere_s%.msh: meshes/tb_sphere.geo
	gmsh -3 -setnumber scale $* $< -o $@ > /dev/null
# two equal bodies, mirror images of each other with their meshes (the symmetry check, tests/verification/twobody_mirror.ini)
meshes/tb_mirror2d.msh: meshes/tb_mirror2d.geo
	gmsh -2 $< -o $@ > /dev/null
meshes/tb_mirror3d.msh: meshes/tb_mirror3d.geo tests/mirror_msh.py
	gmsh -3 -format msh22 $< -o $@.upper > /dev/null
	/usr/bin/python3 tests/mirror_msh.py --tags 20:10,2:1,6:7,8:9,2v:1 $@.upper $@
	rm -f $@.upper
meshes/tb_blocks2d_r%.msh: meshes/tb_blocks2d.msh tests/rotate_msh.py
	$(PYTHON) tests/rotate_msh.py --axis 0,0,1 --angle $* $< $@
# rigidly turned copies (the rotation-invariance checks and bench/perf_curved.py): 2D about z, Example 2 by 30 degrees
# about (1,1,1) and by 75 degrees about (1,-2,0.5) (options/cv_ex2_r30.opts, options/cv_ex2_r75.opts turn its data)
meshes/cv_halfdisc_full_r%.msh: meshes/cv_halfdisc_full.msh tests/rotate_msh.py
	$(PYTHON) tests/rotate_msh.py --axis 0,0,1 --angle $* $< $@
meshes/cv_block2d_r%.msh: meshes/cv_block2d.msh tests/rotate_msh.py
	$(PYTHON) tests/rotate_msh.py --axis 0,0,1 --angle $* $< $@
meshes/cv_ex2_%_r30.msh: meshes/ex2_%.msh tests/rotate_msh.py
	$(PYTHON) tests/rotate_msh.py --axis 1,1,1 --angle 30 $< $@
meshes/cv_ex2_%_r75.msh: meshes/ex2_%.msh tests/rotate_msh.py
	$(PYTHON) tests/rotate_msh.py --axis 1,-2,0.5 --angle 75 $< $@
# by 15 and 45 degrees about (1,-2,0.5) too (tests/features/turn32.ini; options/cv_ex2_r15.opts, options/cv_ex2_r45.opts)
meshes/cv_ex2_%_r15.msh: meshes/ex2_%.msh tests/rotate_msh.py
	$(PYTHON) tests/rotate_msh.py --axis 1,-2,0.5 --angle 15 $< $@
meshes/cv_ex2_%_r45.msh: meshes/ex2_%.msh tests/rotate_msh.py
	$(PYTHON) tests/rotate_msh.py --axis 1,-2,0.5 --angle 45 $< $@

# The library's objects are position independent, for the shared library; the static one holds the same objects.
# -fno-semantic-interposition: calls inside the library stay direct and inlinable (no LD_PRELOAD of our own symbols);
# with it our code runs the instruction count of a build without -fPIC (callgrind, Example 1; +1.3% with -fPIC alone).
build/%.o: src/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -fPIC -fno-semantic-interposition -c $< -o $@
build/app/%.o: app/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@
build/unit_tests.o: tests/unit_tests.c | build
	$(CC) $(CFLAGS) -c $< -o $@
build/misuse.o: tests/misuse.c | build
	$(CC) $(CFLAGS) -c $< -o $@
$(LIBA): $(LIBOBJ) | lib
	rm -f $@
	$(AR) rcs $@ $^
# --no-undefined: every symbol the library uses is found now (PETSc, HDF5, MPI), not when a program loads it;
# --as-needed: of PETSc's long external list only what the library calls becomes a dependency
$(LIBSOV): $(LIBOBJ) | lib
	$(CC) -shared -Wl,-soname,$(LIBSONAME) -Wl,--no-undefined -o $@ $^ -Wl,--as-needed $(LDLIBS)
$(LIBSO): $(LIBSOV)
	ln -sf $(notdir $(LIBSOV)) lib/$(LIBSONAME)
	ln -sf $(LIBSONAME) $@
# The driver and the unit tests link the static library: they run without LD_LIBRARY_PATH or an installed library,
# and a test always runs the code just built
bin/signorini: build/app/signorini.o $(LIBA) | bin
	$(CC) -o $@ $^ $(LDLIBS)
bin/unit_tests: build/unit_tests.o $(LIBA) | bin
	$(CC) -o $@ $^ $(LDLIBS)
# the public functions called wrongly (tests/*/library.ini)
bin/misuse_tests: build/misuse.o $(LIBA) | bin
	$(CC) -o $@ $^ $(LDLIBS)
# the developer guide's worked example (doc/developer-guide.md): an obstacle and a controller type of a program's own,
# built against the private headers; not part of `all` (tests/manual.ini builds and runs it)
build/examples/%.o: examples/extend/%.c | build
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c $< -o $@
bin/custom_types: build/examples/custom_types.o $(LIBA) | bin
	$(CC) -o $@ $^ $(LDLIBS)
bin/custom_law: build/examples/custom_law.o $(LIBA) | bin
	$(CC) -o $@ $^ $(LDLIBS)
build bin lib:
	mkdir -p $@

clean:
	rm -rf build bin lib tests/output

-include $(wildcard build/*.d build/*/*.d)

# the compiler flags for PETSc's headers (tests/check_layers.py compiles the public header alone with them)
print-cflags:
	@echo $(PETSC_CC_INCLUDES)
