# pointcalc - plain Makefile, out-of-tree build in $(B)/ (default build/).
#   make          build/pointcalc (with the static FLINT of build-flint/ when
#                 there) and build/libpointcalc.a
#   make check    build and run every test (unit, schemes, codegen, fuzz-lite)
#   make asan     the same tests built with AddressSanitizer + UBSan (build-asan/)
#   make tsan     the threaded test under ThreadSanitizer (build-tsan/)
#   make valgrind the same tests under valgrind's memcheck
#   make fuzz     libFuzzer on derive_source for FUZZ_SECONDS (clang)
#   make bench    in-process benchmarks (bench/)
#   make figures  docs/figures/*.svg (pointcalc plot)
#   make check-fast  the fast tier: unit tests and the scheme corpus (no
#                 generated-C compilation, no fuzzing), about a minute
#   make lint     layers, format, unused exports, file and function sizes
#   make oracle   the SymPy and Maxima derivations (tests/oracle/), where installed
#   make format   clang-format the sources
#   make flint-static  a static libflint.a from Debian's source package
#                 (.ci/flint-static; pointcalc then links it and starts faster)

B       ?= build
CC      ?= cc
BISON   ?= bison
FLEX    ?= flex
OPT     ?= -O2
CFLAGS  ?= $(OPT) -g
WARN    = -Wall -Wextra -Wshadow -Wundef -Wwrite-strings -Wstrict-prototypes \
          -Wmissing-prototypes -Wold-style-definition
ALL_CFLAGS = -std=c11 -D_POSIX_C_SOURCE=200809L $(WARN) $(CFLAGS) $(SAN) \
             -I. -I$(B) -MMD -MP
LDLIBS  = -lflint -lgmp -lm -lpthread
TEST_LDLIBS = -lcmocka $(LDLIBS)
# pointcalc itself links a static FLINT by default when .ci/flint-static has
# built one (.ci/install-deps does as root, or `make flint-static`): it then
# starts without loading libflint.so and what that pulls in (issues 6 and
# 24: milliseconds a process); tests and benches keep the shared libraries;
# FLINT_STATIC= (empty) links the shared FLINT.  With the static FLINT,
# pointcalc is linked wholly static (PC_STATIC=-static): no dynamic loader
# runs at start-up (`--version` costs 0.40 ms of CPU against 1.11 ms linked
# dynamically, and /bin/true's 0.65 ms).  Sanitizer builds cannot link
# statically, and valgrind does not see malloc in a static binary: `make
# valgrind` runs pointcalc-shared.  PC_STATIC= (empty) links libc dynamically.
FLINT_STATIC ?= $(wildcard build-flint/libflint.a)
ifneq ($(FLINT_STATIC),)
PC_STATIC ?= $(if $(SAN),,-static)
PC_LDLIBS = $(PC_STATIC) $(FLINT_STATIC) $(shell $(CC) -print-file-name=libmpfr.a) \
            $(shell $(CC) -print-file-name=libgmp.a) -lm -lpthread
else
PC_LDLIBS = $(LDLIBS)
endif

# the layers (docs/architecture.md): base <- grammar <- compiler <- codegen,
# base <- runtime <- codegen, and driver/ above all; `make lint` checks it.
# libpointcalc.a is the library (base to runtime and driver/api.c); the
# command line is its own archive (for in-process tests and fuzzers) plus
# driver/cli/main.c.
LAYERS  = base grammar compiler codegen runtime
LIB_SRC = $(foreach d,$(LAYERS),$(wildcard $(d)/*.c $(d)/*/*.c)) driver/api.c
CLI_SRC = $(filter-out driver/cli/main.c,$(wildcard driver/cli/*.c))
GEN_SRC = $(B)/grammar/parser.c $(B)/grammar/lexer.c
LIB_OBJ = $(LIB_SRC:%.c=$(B)/%.o) $(GEN_SRC:.c=.o)
CLI_OBJ = $(CLI_SRC:%.c=$(B)/%.o)
LIBS    = $(B)/libpointcalc-cli.a $(B)/libpointcalc.a
# what `make format` rewrites and `make lint` checks
FORMAT_SRC = $(wildcard $(addsuffix /*.[ch],$(LAYERS) $(addsuffix /*,$(LAYERS)) \
               driver driver/cli tests/unit tests/fuzz bench examples)) libpointcalc.h
TESTS   = $(patsubst tests/unit/%.c,$(B)/tests/%,$(wildcard tests/unit/test_*.c))
BENCHES = $(patsubst bench/%.c,$(B)/bench/%,$(wildcard bench/bench_*.c))

all: $(B)/pointcalc $(B)/libpointcalc.a

# grouped targets (&:): one bison run makes both files, also under -j
$(B)/grammar/parser.c $(B)/grammar/parser.h &: grammar/parser.y
	@mkdir -p $(@D)
	$(BISON) -Wall -Werror --defines=$(B)/grammar/parser.h -o $(B)/grammar/parser.c $<

$(B)/grammar/lexer.c $(B)/grammar/lexer.h &: grammar/lexer.l $(B)/grammar/parser.h
	@mkdir -p $(@D)
	$(FLEX) --header-file=$(B)/grammar/lexer.h -o $(B)/grammar/lexer.c $<

# every object may include the generated headers
$(LIB_SRC:%.c=$(B)/%.o) $(CLI_OBJ) $(B)/driver/cli/main.o: $(B)/grammar/parser.h $(B)/grammar/lexer.h

$(B)/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<

# generated code is not ours to warn about beyond -Wall
$(B)/grammar/%.o: $(B)/grammar/%.c
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -Wno-unused-function -Wno-missing-prototypes -c -o $@ $<

$(B)/libpointcalc.a: $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(B)/libpointcalc-cli.a: $(CLI_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(B)/pointcalc: $(B)/driver/cli/main.o $(LIBS) $(FLINT_STATIC)
	$(CC) $(ALL_CFLAGS) -o $@ $(B)/driver/cli/main.o $(LIBS) $(PC_LDLIBS)

# the shared-library build beside a static one, for bench_start
$(B)/pointcalc-shared: $(B)/driver/cli/main.o $(LIBS)
	$(CC) $(ALL_CFLAGS) -o $@ $^ $(LDLIBS)

$(B)/tests/%: tests/unit/%.c $(LIBS)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -o $@ $< $(LIBS) $(TEST_LDLIBS)

$(B)/bench/%: bench/%.c $(LIBS)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -o $@ $< $(LIBS) $(LDLIBS)

# linked as pointcalc is (the static FLINT when there): its in-process
# columns and the whole process it spawns run the same code
$(B)/bench/bench_derive: bench/bench_derive.c $(LIBS)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -o $@ $< $(LIBS) $(PC_LDLIBS)

# the library example of docs/api.md, built and run by `make check`
$(B)/examples/api_example: examples/api_example.c $(B)/libpointcalc.a
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -o $@ $< $(B)/libpointcalc.a $(LDLIBS)

tests: $(TESTS) $(B)/pointcalc $(B)/examples/api_example

# Tests run from the repo root; each binary is a cmocka group.
# The fast tier leaves out the tests that compile generated C (test_emit_c,
# test_collapse) and the fuzz corpus (test_fuzz): every unit test of the
# algebra, the printers, the front end and the runtime, and every scheme's
# expectations (test_schemes), in well under a minute of CPU.
SLOW_TESTS = $(B)/tests/test_emit_c $(B)/tests/test_collapse $(B)/tests/test_fuzz
FAST_TESTS = $(filter-out $(SLOW_TESTS),$(TESTS))
check-fast: $(FAST_TESTS) $(B)/pointcalc
	@fail=0; for t in $(FAST_TESTS); do \
	  echo "== $$t"; PC_BIN=$(B)/pointcalc $$t || fail=1; done; exit $$fail

# `make check` runs its suites JOBS at a time (tests/run_jobs.sh), the
# longest first; each one's output is printed whole when it ends.
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
check: tests
	@PC_BIN=$(B)/pointcalc tests/run_jobs.sh $(JOBS) $(SLOW_TESTS) \
	  "tests/cli_test.sh $(B)/pointcalc" \
	  "python3 tests/printback.py $(B)/pointcalc examples/*.pcs tests/schemes/*.pcs" \
	  "tests/latex_test.sh $(B)/pointcalc" "tests/natural_test.sh $(B)/pointcalc" \
	  "tests/tutorial_test.sh $(B)/pointcalc" "tests/plot_test.sh $(B)/pointcalc" \
	  $(FAST_TESTS) "tests/api_example_test.sh $(B)/examples/api_example"

# (fewer fuzz mutations than `make check`: under ASan a mutation of a
# chapter-2 or chapter-3 scheme costs 50-270 ms (derived, printed three ways
# and plotted), and CI has 90 minutes for all three runs)
asan:
	PC_FUZZ_MUTATIONS=$${PC_FUZZ_MUTATIONS:-150} $(MAKE) B=build-asan OPT=-O1 \
	  SAN="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" check

# the library from several threads at once (tests/unit/test_threads.c)
# under ThreadSanitizer: any data race fails it
tsan:
	$(MAKE) B=build-tsan OPT=-O1 \
	  SAN="-fsanitize=thread -fno-omit-frame-pointer" build-tsan/tests/test_threads
	TSAN_OPTIONS="halt_on_error=1 $${TSAN_OPTIONS:-}" build-tsan/tests/test_threads

# the same suite under valgrind (fewer fuzz mutations: valgrind is ~30x slower)
VALGRIND = valgrind -q --error-exitcode=1 --leak-check=full \
           --errors-for-leak-kinds=definite,indirect
# the CLI tests run the binary through a wrapper that execs it under valgrind
valgrind: tests $(B)/pointcalc-shared
	@printf '#!/bin/sh\nexec $(VALGRIND) --error-exitcode=99 $(CURDIR)/$(B)/pointcalc-shared "$$@"\n' \
	  > $(B)/pointcalc-vg && chmod +x $(B)/pointcalc-vg
	@printf '#!/bin/sh\nexec valgrind -q --error-exitcode=99 --leak-check=no $(CURDIR)/$(B)/pointcalc-shared "$$@"\n' \
	  > $(B)/pointcalc-vg-noleak && chmod +x $(B)/pointcalc-vg-noleak
	@PC_FUZZ_MUTATIONS=15 PC_FUZZ_CUTS=40 PC_VALGRIND=1 PC_BIN=$(B)/pointcalc \
	  tests/run_jobs.sh $(JOBS) $(addprefix "$(VALGRIND) ,$(addsuffix ",$(SLOW_TESTS))) \
	  "PC_NOLEAK=$(B)/pointcalc-vg-noleak tests/cli_test.sh $(B)/pointcalc-vg" \
	  "tests/plot_test.sh $(B)/pointcalc-vg" "tests/natural_test.sh $(B)/pointcalc-vg" \
	  $(addprefix "$(VALGRIND) ,$(addsuffix ",$(FAST_TESTS))) \
	  "tests/api_example_test.sh $(B)/examples/api_example $(VALGRIND)"

# coverage-guided fuzzing (clang + libFuzzer + ASan/UBSan) of three targets:
# derive_source and every back end (tests/fuzz/fuzz_derive.c), the light
# one (tests/fuzz/fuzz_light.c: derive, the text printer and the C; inputs
# of at most 512 bytes, seeds without the heavy chapter-2 schemes), and
# eval's command line (tests/fuzz/fuzz_eval_args.c); seeds from examples/
# and tests/, the language's dictionary.  FUZZ_SECONDS bounds each run,
# FUZZ_RUNS the executions, FUZZ_TARGETS which run (tests/fuzz/campaign.sh
# runs them at nice 19 on one core and prints each one's executions, rate
# and coverage).  Crashes land in build-fuzz/artifacts/.
FUZZ_SECONDS ?= 120
FUZZ_RUNS ?= 1000000
FUZZ_TARGETS ?= fuzz_light fuzz_derive fuzz_eval_args
FUZZ_CC = clang -std=c11 -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Werror \
	  -I. -Ibuild-fuzz -g -O1 -fsanitize=fuzzer,address,undefined
fuzz-build:
	$(MAKE) B=build-fuzz CC=clang OPT=-O1 \
	  SAN="-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer" \
	  build-fuzz/libpointcalc.a build-fuzz/libpointcalc-cli.a
	$(FUZZ_CC) -o build-fuzz/fuzz_derive tests/fuzz/fuzz_derive.c build-fuzz/libpointcalc.a $(LDLIBS)
	$(FUZZ_CC) -DFUZZ_DERIVE_SECONDS=0.25 -DFUZZ_BACKEND_SECONDS=0.25 \
	  -o build-fuzz/fuzz_light tests/fuzz/fuzz_light.c build-fuzz/libpointcalc.a $(LDLIBS)
	$(FUZZ_CC) -o build-fuzz/fuzz_eval_args tests/fuzz/fuzz_eval_args.c build-fuzz/libpointcalc-cli.a build-fuzz/libpointcalc.a $(LDLIBS)
fuzz: fuzz-build
	FUZZ_RUNS=$(FUZZ_RUNS) FUZZ_SECONDS=$(FUZZ_SECONDS) \
	  tests/fuzz/campaign.sh $(FUZZ_TARGETS)

# the independent derivations (SymPy, Maxima) where they are installed
oracle: $(B)/pointcalc
	tests/oracle/run.sh $(B)

# PYTHON: the interpreter for bench/lambdify.py; by default the first python3
# on PATH that has sympy and numpy (else the first with sympy)
bench: $(BENCHES) $(B)/pointcalc $(if $(FLINT_STATIC),$(B)/pointcalc-shared)
	@py=$${PYTHON:-}; \
	if [ -z "$$py" ]; then for m in 'sympy, numpy' sympy; do \
	  for p in python3 /usr/bin/python3; do \
	    if $$p -c "import $$m" 2>/dev/null; then py=$$p; break 2; fi; \
	  done; done; fi; \
	for b in $(BENCHES); do case $$b in \
	  *bench_start) $$b $(B)/pointcalc $(if $(FLINT_STATIC),$(B)/pointcalc-shared) || exit 1;; \
	  *bench_derive) PC_BENCH_NO_WHOLE=1 $$b || exit 1;; \
	  *) PYTHON=$$py $$b || exit 1;; esac; done
	@PYTHON=$${PYTHON:-python3} bench/run_whole.sh $(B)
	@if [ -x bench/run_maxima.sh ]; then bench/run_maxima.sh $(B); fi

# the figures of docs/plot.md (tests/plot_test.sh checks they are current)
figures: $(B)/pointcalc
	sh docs/figures/make-figures.sh $(B)/pointcalc docs/figures

format:
	clang-format -i $(FORMAT_SRC)

# the house rules the compiler does not check (tests/lint/): includes only
# down the layers (and a self-test that a planted upward one fails), no
# format drift, no export nobody uses, no file over 1000 lines and no
# function over 120 without a 'long:' reason
LINT_C = $(filter %.c,$(foreach d,$(LAYERS) driver driver/cli,$(wildcard $(d)/*.c $(d)/*/*.c)))
lint: $(B)/pointcalc $(B)/libpointcalc.a
	tests/lint/layers.sh
	tests/lint/selftest.sh
	tests/lint/alloc.sh
	@tests/lint/format.sh $(FORMAT_SRC)
	tests/lint/exports.sh $(B)
	python3 tests/lint/funclen.py $(sort $(LINT_C))

flint-static:
	.ci/flint-static

clean:
	rm -rf build build-asan build-tsan build-fuzz

.PHONY: all tests check check-fast lint oracle asan tsan valgrind fuzz fuzz-build bench figures format clean flint-static
-include $(shell find $(B) -name '*.d' 2>/dev/null)
