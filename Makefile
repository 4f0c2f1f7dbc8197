# tristep: make | make run [LESSON=02] | make test [SANITIZE=1] | make figures | make bench
#          make exercise LESSON=02 [FILE=x.c] [SCENE=s] [STEP=n] [SAMPLES=n] | make check LESSON=02 [FILE=x.c] [SCENE=s] [SEED=n] [SEARCH=s]
#          make grade LESSON=02 DIR=submissions/ [TIMEOUT=60] [CSV=file] [OUT=folder] [SEED=n] [POINTS=file] [UNSAFE=1]
#          make gradescope LESSON=02 [SEED=n] [POINTS=file] (an autograder zip) | make grade-hostile [HOSTILE="02 06 09"]
#          (check, exercise and grade take VARIANT=name: a lesson's graded variant, lessons/README.md)
#          make student-kit [KIT=folder] (the course without its answers, to hand out) | make student-kit-test
#          make bench-lines (lines beside llvmpipe) | make skeletons (lessons/*/exercise.c from the answers)
#          make soak [MINUTES=10] | make fuzz [SECONDS=N] | make aarch64 | make simde-test | make clean
MAKEFLAGS += --no-builtin-rules   # no implicit "%: %.o" that would try to remake the .d files
ifeq ($(MAKELEVEL),0)             # build on every core unless told (make -j1); sub-makes share the jobs
MAKEFLAGS += -j$(shell nproc 2>/dev/null || echo 2)
endif
LESSONS  := $(notdir $(wildcard lessons/[0-9][0-9]-*))
# The worked answers are here, or not (a student kit, make student-kit):
# without them the test files that need them are left out of the build by
# name, and so are the blocks "#if !TRISTEP_NO_ANSWERS" of the others.
ANSWERS_HERE := $(if $(wildcard lessons/*/answer.c),1)
NEED_ANSWERS := tests/test_exercise.c tests/test_grade.c tests/test_variants.c tests/test_kit.c
TESTS_SRC := $(filter-out $(if $(ANSWERS_HERE),,$(NEED_ANSWERS)),$(wildcard tests/*.c))
BUILD    ?= build
B        := $(BUILD)$(if $(PORT),/$(PORT),$(if $(FUZZ),/fuzz,$(if $(SANITIZE),/sanitize)))
PROGRAMS := $(LESSONS:%=$(B)/%)
LIB_OBJ  := $(patsubst %.c,$(B)/obj/%.o,$(filter-out src/cli/main.c src/exercise/main.c src/exercise/runner.c,$(wildcard src/*.c src/*/*.c)))
EX_SRC   := $(wildcard lessons/*/exercise.c lessons/*/answer.c)
VAR_SRC  := $(wildcard lessons/*/exercise-*.c lessons/*/answer-*.c)
LES_SRC  := $(filter-out $(EX_SRC) $(VAR_SRC),$(wildcard lessons/*/*.c))
EXP_SRC  := $(wildcard lessons/*/*_explorer.c)
MUTATIONS:= $(patsubst tests/mutations/%.patch,%,$(wildcard tests/mutations/*.patch))
TEST_OBJ := $(patsubst %.c,$(B)/obj/%.o,$(TESTS_SRC) tests/bench/bigscene.c tests/bench/agree.c tests/bench/scenes.c) $(B)/obj/lessons.o $(B)/obj/exercises.o $(EX_SRC:%.c=$(B)/obj/%.o) \
            $(B)/obj/mutations.o $(MUTATIONS:%=$(B)/mutations/%.o) $(VAR_SRC:%.c=$(B)/obj/%.o) $(B)/obj/exercise-variants.o
ALL_LES  := $(LES_SRC:%.c=$(B)/obj/%.o) $(patsubst %.c,$(B)/fast/%.o,$(filter-out $(EXP_SRC),$(LES_SRC)))
# the first lesson, 01 (lesson 00, lines, is a warm-up before it)
LESSON   ?= $(firstword $(subst -, ,$(firstword $(filter-out 00-%,$(LESSONS)))))
nn        = $(firstword $(subst -, ,$(notdir $(patsubst %/,%,$(dir $1)))))

# CFLAGS, LDFLAGS and LDLIBS are the user's (make CFLAGS=-O0 still builds);
# what tristep needs goes into TS_* beside them.
CFLAGS   ?= -O2 -g
SANITIZERS := -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all \
              -fno-omit-frame-pointer
ifneq ($(SANITIZE),)
SAN      := $(SANITIZERS)
endif
ifdef FUZZ                # make fuzz: libFuzzer needs clang
override CC := clang
SAN      := $(SANITIZERS) -fsanitize=fuzzer-no-link
endif
ifeq ($(PORT),aarch64)    # make aarch64: Debian's cross compiler, SSE2 through SIMDe to NEON
override CC := aarch64-linux-gnu-gcc
SAN      :=
TS_PORT  := -I$(B)/include
LDFLAGS  += -static
RUN      := qemu-aarch64
endif
ifeq ($(PORT),simde)      # make simde-test: SSE2 through SIMDe's portable C, sanitized
SAN      := $(SANITIZERS)
TS_PORT  := -DTRISTEP_SIMDE -DSIMDE_NO_NATIVE
endif
TS_CFLAGS = -std=c17 -Wall -Wextra -pedantic -MMD -MP -Isrc -pthread $(PKG_CFLAGS) $(SAN) $(TS_PORT)
CC_ALL    = $(CC) $(CFLAGS) $(TS_CFLAGS)
LD_ALL    = $(CC) $(LDFLAGS) $(SAN)
LIBS      = $(LDLIBS) $(PKG_LIBS) -pthread
# What comes before any compiling (order-only): the library flags, and the
# packages of make test and make bench (so make -j2 test installs them first).
FIRST    := $(B)/config.mk $(if $(filter test,$(MAKECMDGOALS)),deps-test) $(if $(filter bench,$(MAKECMDGOALS)),deps-bench)

all: $(PROGRAMS)
.PHONY: all run test fresh-test figures bench bench-lines soak fuzz fuzz-run aarch64 simde-test port-run clean deps-test deps-bench deps-fuzz exercise check grade grade-build grade-hostile gradescope skeletons student-kit student-kit-test FORCE
.SECONDEXPANSION:

ifneq ($(filter-out clean fresh-test,$(or $(MAKECMDGOALS),all)),)
include $(B)/config.mk
endif
# make test's packages, its sub-makes' (aarch64, simde) included, come in
# one apt-get run, before anything else: the first thing make does is to
# remake this included fragment. make -n, -q and -t remake it too, but
# install nothing: MAKEFLAGS (its first word, the one-letter options) says
# so while the Makefile is read, no longer in the recipe.
DRY_RUN  := $(strip $(foreach f,n q t,$(findstring $f,$(filter-out -%,$(firstword $(MAKEFLAGS))))))
$(B)/config.mk: src/deps.sh ; @TRISTEP_DRY_RUN=$(DRY_RUN) sh src/deps.sh $(or $(PORT),$(if $(filter fuzz,$(MAKECMDGOALS)),fuzz,$(if $(filter test soak,$(MAKECMDGOALS)),test,build))) $@
deps-test deps-bench deps-fuzz: ; @sh src/deps.sh $(@:deps-%=%)

# The compiler and its flags, rewritten only when they change (make CC=clang
# after make rebuilds everything with clang).
$(B)/cc.flag: FORCE | $(B)/config.mk ; @echo '$(CC_ALL)' | cmp -s - $@ || echo '$(CC_ALL)' > $@
# Lessons are compiled twice: narrated for the programs and tests, fast
# (narration compiled out, descriptor renamed lesson_NN_fast) for the bench.
# What the explorer adds for a lesson (NAME_explorer.c) only narrated.
$(B)/obj/%.o: %.c $(B)/cc.flag | $(FIRST) ; @mkdir -p $(@D) && $(CC_ALL) -DTRISTEP_NARRATE -c $< -o $@
$(B)/fast/%.o: %.c $(B)/cc.flag | $(FIRST) ; @mkdir -p $(@D) && $(CC_ALL) -Dlesson_$(call nn,$<)=lesson_$(call nn,$<)_fast -c $< -o $@
$(B)/obj/main-%.o: src/cli/main.c $(B)/cc.flag | $(FIRST) ; @mkdir -p $(@D) && $(CC_ALL) -DLESSON=lesson_$* -c $< -o $@
# The library anew when its list of objects changes (lib.list, rewritten
# only then): no member is left over from a file moved away.
$(B)/lib.list: FORCE ; @echo '$(LIB_OBJ)' | cmp -s - $@ || echo '$(LIB_OBJ)' > $@
$(B)/libtristep.a: $(LIB_OBJ) $(B)/lib.list ; @rm -f $@ && $(AR) rcs $@ $(LIB_OBJ)
$(PROGRAMS): $(B)/%: $(B)/obj/main-$$(firstword $$(subst -, ,$$*)).o $(B)/obj/lessons.o $(ALL_LES) $(B)/libtristep.a
	$(LD_ALL) $^ $(LIBS) -o $@

# Every lesson, both builds, listed for the tests and the bench (again when
# a lesson folder appears: that changes the mtime of lessons/).
$(B)/lessons.c: Makefile lessons $(wildcard lessons/*/) | $(B)/config.mk
	@printf '#include "%s"\n' $(if $(PORT),lesson.h,lesson_explorer.h) > $@
	@for n in $(foreach l,$(LESSONS),$(call nn,$(l)/x)); do printf 'extern const struct lesson lesson_%s, lesson_%s_fast;\n' $$n $$n; done >> $@
	@printf 'const struct lesson *const all_lessons[] = { %s NULL };\n' "$(foreach l,$(LESSONS),&lesson_$(call nn,$(l)/x),)" >> $@
	@printf 'const struct lesson *const all_lessons_fast[] = { %s NULL };\n' "$(foreach l,$(LESSONS),&lesson_$(call nn,$(l)/x)_fast,)" >> $@
	$(if $(PORT),,@for f in $(EXP_SRC); do printf 'extern const struct lesson_explorer lesson_%s_explorer;\n' $$(basename $$(dirname $$f) | cut -d- -f1); done >> $@)
	$(if $(PORT),,@printf 'const struct lesson_explorer *const all_lesson_explorers[] = { %s NULL };\n' "$(foreach f,$(EXP_SRC),&lesson_$(call nn,$(f))_explorer,)" >> $@)
$(B)/obj/lessons.o: $(B)/lessons.c | $(FIRST) ; $(CC_ALL) -c $< -o $@
$(B)/tristep-tests: $(TEST_OBJ) $(ALL_LES) $(B)/libtristep.a | $$(SKELETONS) ; $(LD_ALL) $^ $(LIBS) -lcriterion -o $@
# The bench (tests/bench/): every lesson's fast build, beside llvmpipe when OSMesa is there.
# Whether OSMesa is there is recorded in osmesa.flag, rewritten only when it
# changes, so the bench is rebuilt once `make bench` has installed it.
OSMESA   := $(shell pkg-config --exists osmesa 2>/dev/null && echo -lOSMesa)
$(B)/osmesa.flag: FORCE ; @echo '$(OSMESA)' | cmp -s - $@ || echo '$(OSMESA)' > $@
$(B)/obj/tests/bench/%.o: TS_CFLAGS += $(if $(OSMESA),-DTRISTEP_OSMESA)
$(patsubst %.c,$(B)/obj/%.o,$(wildcard tests/bench/*.c)): $(B)/osmesa.flag
$(B)/tristep-bench: $(patsubst %.c,$(B)/obj/%.o,$(wildcard tests/bench/*.c)) $(B)/obj/lessons.o $(ALL_LES) $(B)/libtristep.a
	$(LD_ALL) $^ $(LIBS) $(OSMESA) -o $@

# Lines beside llvmpipe's GL_LINES (tests/lines/peer.c): make bench-lines.
$(B)/obj/tests/lines/peer.o: TS_CFLAGS += $(if $(OSMESA),-DTRISTEP_OSMESA)
$(B)/obj/tests/lines/peer.o: $(B)/osmesa.flag
$(B)/lines-peer: $(B)/obj/tests/lines/peer.o $(B)/libtristep.a ; $(LD_ALL) $^ $(LIBS) $(OSMESA) -o $@
bench-lines: deps-bench ; @$(MAKE) --no-print-directory $(B)/lines-peer && $(B)/lines-peer

# The search for lesson 06's walk-order cracks (tests/search/cracks.c).
$(B)/crack-search: $(B)/obj/tests/search/cracks.o $(B)/obj/lessons.o $(ALL_LES) $(B)/libtristep.a ; $(LD_ALL) $^ $(LIBS) -o $@

# Lesson 07's workers under ThreadSanitizer (lesson 08's tiled twin on them
# too): a program of its own (Criterion does not run under TSan), run by
# tests/test_lesson07.c.
NO_CAIRO := $(filter-out src/scene/png.c,$(wildcard src/scene/*.c)) tests/portable/png_none.c   # PNG textures need cairo
TSAN_SRC := tests/tsan/tsan_tiles.c $(filter-out $(EX_SRC) $(EXP_SRC),$(wildcard lessons/07-tiles/*.c lessons/08-multisampling/*.c lessons/09-textures/*.c)) src/raster/raster.c $(NO_CAIRO) src/util/file.c src/shade/quad.c src/trace/trace.c
$(B)/tsan-tiles: $(TSAN_SRC) src/lesson.h $(wildcard lessons/07-tiles/*.h lessons/08-multisampling/*.h lessons/09-textures/*.h) | $(FIRST)
	$(CC) $(CFLAGS) -std=c17 -Wall -Wextra -pedantic -Isrc -pthread $(PKG_CFLAGS) -O1 -fsanitize=thread $(TSAN_SRC) -lm -o $@

# The soak (tests/soak/): every lesson's window under Xvfb, random input, sanitizers.
$(B)/tristep-soak: $(B)/obj/tests/soak/soak.o ; $(LD_ALL) $^ -lm -o $@

# Fuzzing (tests/fuzz/fuzz.h): one libFuzzer program per harness, and a
# replay of the committed corpus that needs no libFuzzer (run by make test).
FUZZERS  := $(patsubst tests/fuzz/corpus/%,%,$(wildcard tests/fuzz/corpus/*))
FUZZ_OBJ := $(patsubst %.c,$(B)/obj/%.o,$(filter-out %/libfuzzer.c %/replay.c,$(wildcard tests/fuzz/*.c))) \
            $(B)/obj/tests/testlib.o $(B)/obj/lessons.o $(ALL_LES) $(B)/libtristep.a
$(B)/obj/fuzz-%.o: tests/fuzz/libfuzzer.c | $(FIRST) ; @mkdir -p $(@D) && $(CC_ALL) -DFUZZ_HARNESS=fuzz_$* -c $< -o $@
$(B)/fuzz-%: $(B)/obj/fuzz-%.o $(FUZZ_OBJ) ; $(LD_ALL) -fsanitize=fuzzer $^ $(LIBS) -o $@
$(B)/fuzz-replay: $(B)/obj/tests/fuzz/replay.o $(FUZZ_OBJ) ; $(LD_ALL) $^ $(LIBS) -o $@
SECONDS  ?= 60
fuzz: deps-fuzz ; @$(MAKE) --no-print-directory FUZZ=1 fuzz-run
fuzz-run: $(FUZZERS:%=$(B)/fuzz-%)
	@for f in $(FUZZERS); do mkdir -p $(B)/corpus/$$f $(B)/crashes; \
	  echo "fuzz: $$f for $(SECONDS) s (new inputs in $(B)/corpus/$$f, failures in $(B)/crashes)"; \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp nice -n 10 $(B)/fuzz-$$f -max_total_time=$(SECONDS) -print_final_stats=1 -artifact_prefix=$(B)/crashes/$$f- \
	    $$([ -f tests/fuzz/$$f.dict ] && echo -dict=tests/fuzz/$$f.dict) $(B)/corpus/$$f tests/fuzz/corpus/$$f || exit 1; done

# Portable: the core, the lessons (both builds) and the
# exactness driver tests/portable/exact.c, no SDL, cairo or Criterion:
# `make aarch64` cross-compiles them statically and runs them under qemu,
# `make simde-test` runs them natively through SIMDe's portable code.
CORE_SRC := $(filter-out %_explorer.c,$(wildcard src/*.c $(foreach d,util raster front trace shade,src/$(d)/*.c))) $(NO_CAIRO)
ALG_SRC  := $(filter-out $(EXP_SRC),$(LES_SRC))
$(B)/exact: $(patsubst %.c,$(B)/obj/%.o,tests/portable/exact.c tests/testlib.c $(CORE_SRC)) \
            $(B)/obj/lessons.o $(ALG_SRC:%.c=$(B)/obj/%.o) $(ALG_SRC:%.c=$(B)/fast/%.o)
	$(LD_ALL) $^ -lm -o $@
$(B)/include/simde: ; @mkdir -p $(@D) && ln -sfn /usr/include/simde $@   # without the rest of /usr/include
aarch64 simde-test: ; @$(MAKE) --no-print-directory PORT=$(@:-test=) port-run
port-run: $(if $(filter aarch64,$(PORT)),$(B)/include/simde) $(B)/exact ; $(RUN) $(B)/exact

# Exercises (lessons/NN-name/exercise.c): the student's FILE, compiled with
# src/exercise/student.h in front, linked into build/exercise-NN; the tests
# link every skeleton and answer under its own name (build/exercises.c). A
# FILE anywhere sees its lesson's headers (lesson 09's textures.h).
STUDENT   = -DTRISTEP_NARRATE -include exercise/student.h
EX_LESSON = $(filter lessons/$(LESSON)-%,$(wildcard lessons/[0-9][0-9]-*))
FILE     ?= $(EX_LESSON)/exercise$(if $(VARIANT),-$(VARIANT)).c
EX_VARIANT = $(if $(VARIANT),--exercise-variant '$(VARIANT)')
$(EX_SRC:%.c=$(B)/obj/%.o): $(B)/obj/%.o: %.c | $(FIRST)
	@mkdir -p $(@D) && $(CC_ALL) $(STUDENT) -Dexercise_rasterize=exercise_$(call nn,$<)_$(basename $(notdir $<)) \
	  -Dexercise_clip=exercise_$(call nn,$<)_$(basename $(notdir $<))_clip -c $< -o $@
$(B)/exercises.c: Makefile $(wildcard lessons/*/) $(EX_SRC) | $(FIRST)
	@printf '#include "exercise/exercise.h"\n' > $@
	@printf 'struct poly;\nstruct plane;\n' >> $@
	@for f in $(EX_SRC); do n=$$(basename $$(dirname $$f) | cut -c1-2); printf 'void exercise_%s_%s(const struct tri_setup *, const struct raster_params *, struct target *, struct trace *);\n' $$n $$(basename $$f .c); \
	  if grep -q '^void exercise_clip(' $$f; then printf 'void exercise_%s_%s_clip(struct poly *, const struct poly *, const struct plane *);\n' $$n $$(basename $$f .c); fi; done >> $@
	@printf 'const struct exercise_code all_exercises[] = {\n' >> $@
	@for d in $(sort $(dir $(EX_SRC))); do n=$$(basename $$d | cut -c1-2); \
	  a=NULL; [ -f $${d}answer.c ] && a=exercise_$${n}_answer; \
	  if grep -q '^void exercise_clip(' $${d}exercise.c; then c="exercise_$${n}_exercise_clip, $${a}_clip"; else c="NULL, NULL"; fi; \
	  [ $$a = NULL ] && c=$$(echo "$$c" | sed 's/NULL_clip/NULL/'); \
	  printf '    { "%s", exercise_%s_exercise, %s, %s },\n' $$n $$n $$a "$$c"; done >> $@
	@printf '    { NULL, NULL, NULL, NULL, NULL },\n};\n' >> $@
$(B)/obj/exercises.o: $(B)/exercises.c | $(FIRST) ; $(CC_ALL) -c $< -o $@
# The skeletons: lessons/NN-name/exercise.c made from the worked answer
# beside it, its one source (src/exercise/skeleton.awk says how); the build
# makes them into $(B)/skeletons/, the tests hold the committed ones to
# them, and `make skeletons` writes them over the committed ones.
SKELETONS := $(patsubst lessons/%/answer.c,$(B)/skeletons/%/exercise.c,$(wildcard lessons/*/answer.c))
$(B)/skeletons/%/exercise.c: lessons/%/answer.c src/exercise/skeleton.awk
	@mkdir -p $(@D) && awk -f src/exercise/skeleton.awk $< > $@.tmp && mv $@.tmp $@
# ... and each graded variant's, exercise-V.c from answer-V.c
VAR_SKEL  := $(patsubst lessons/%,$(B)/skeletons/%,$(subst /answer-,/exercise-,$(wildcard lessons/*/answer-*.c)))
SKELETONS += $(VAR_SKEL)
$(VAR_SKEL): $(B)/skeletons/%: $$(subst /exercise-,/answer-,lessons/%) src/exercise/skeleton.awk
	@mkdir -p $(@D) && awk -f src/exercise/skeleton.awk $< > $@.tmp && mv $@.tmp $@
skeletons: $(SKELETONS) ; @for f in $(SKELETONS); do cp $$f lessons/$${f#$(B)/skeletons/}; done
# The mutation suite (tests/mutations/NN-name.patch): each a classic mistake
# made in lesson NN's worked answer, compiled like a student's file under
# its own name and listed in build/mutations.c with the check it must fail.
# (NN-V--what.patch: a mistake in graded variant V's answer, answer-V.c)
mut_var    = $(if $(findstring --,$1),$(patsubst $(firstword $(subst -, ,$1))-%,%,$(firstword $(subst --, ,$1))))
mut_answer = $(wildcard lessons/$(firstword $(subst -, ,$1))-*/answer$(if $(call mut_var,$1),-$(call mut_var,$1)).c)
mut_fn     = mutation_$(subst -,_,$1)
# a mistake leaves a part of the answer unused: not worth a warning
MUT_WARN   = -Wno-unused-parameter -Wno-unused-variable -Wno-unused-but-set-variable -Wno-unused-function
$(B)/mutations/%.c: tests/mutations/%.patch $$(call mut_answer,$$*) | $(FIRST)
	@mkdir -p $(@D) && patch --batch --quiet --no-backup-if-mismatch -r - -o $@ $(call mut_answer,$*) < $< >/dev/null \
	  || { rm -f $@; echo "$<: does not apply to $(call mut_answer,$*)"; exit 1; }
$(B)/mutations/%.o: $(B)/mutations/%.c | $(FIRST)
	@$(CC_ALL) $(MUT_WARN) $(STUDENT) -I$(dir $(call mut_answer,$*)) -Dexercise_rasterize=$(call mut_fn,$*) -Dexercise_clip=$(call mut_fn,$*)_clip -c $< -o $@
$(B)/mutations.c: Makefile $(MUTATIONS:%=tests/mutations/%.patch) $(MUTATIONS:%=$(B)/mutations/%.c) | $(FIRST)
	@printf '#include "exercise/exercise.h"\nstruct poly;\nstruct plane;\n' > $@
	@for m in $(MUTATIONS); do f=mutation_$$(echo $$m | tr - _); printf 'void %s(const struct tri_setup *, const struct raster_params *, struct target *, struct trace *);\n' $$f; \
	  if grep -q '^void exercise_clip(' $(B)/mutations/$$m.c; then printf 'void %s_clip(struct poly *, const struct poly *, const struct plane *);\n' $$f; fi; done >> $@
	@printf 'const struct exercise_mutation all_mutations[] = {\n' >> $@
	@for m in $(MUTATIONS); do f=mutation_$$(echo $$m | tr - _); c=NULL; \
	  if grep -q '^void exercise_clip(' $(B)/mutations/$$m.c; then c=$${f}_clip; fi; \
	  k=$$(sed -n 's/^check: *//p' tests/mutations/$$m.patch | head -n 1); \
	  v=$$(echo $$m | sed -n 's/^[0-9][0-9]-\(.*\)--.*/"\1"/p'); \
	  printf '    { "%s", "%s", "%s", %s, %s, %s },\n' "$$(echo $$m | cut -c1-2)" "$$m" "$$k" $$f $$c "$${v:-NULL}"; done >> $@
	@printf '    { NULL, NULL, NULL, NULL, NULL, NULL },\n};\n' >> $@
$(B)/obj/mutations.o: $(B)/mutations.c | $(FIRST) ; @$(CC_ALL) -c $< -o $@
# The graded variants (lessons/NN-name/exercise-V.c, answer-V.c), compiled
# like the skeletons under their own names and listed in
# build/exercise-variants.c for the tests.
var_fn     = exercise_$(call nn,$1)_$(subst -,_,$(basename $(notdir $1)))
$(VAR_SRC:%.c=$(B)/obj/%.o): $(B)/obj/%.o: %.c | $(FIRST)
	@mkdir -p $(@D) && $(CC_ALL) $(STUDENT) -Dexercise_rasterize=$(call var_fn,$<) -Dexercise_clip=$(call var_fn,$<)_clip -c $< -o $@
$(B)/exercise-variants.c: Makefile $(wildcard lessons/*/) | $(FIRST)
	@printf '#include "exercise/exercise.h"\n' > $@
	@for f in $(VAR_SRC); do printf 'void exercise_%s_%s(const struct tri_setup *, const struct raster_params *, struct target *, struct trace *);\n' \
	  $$(basename $$(dirname $$f) | cut -c1-2) $$(basename $$f .c | tr - _); done >> $@
	@printf 'const struct exercise_variant_code all_exercise_variants[] = {\n' >> $@
	@for f in $(wildcard lessons/*/exercise-*.c); do n=$$(basename $$(dirname $$f) | cut -c1-2); v=$$(basename $$f .c); v=$${v#exercise-}; \
	  s=exercise_$${n}_exercise_$$(echo $$v | tr - _); a=NULL; \
	  [ -f $$(dirname $$f)/answer-$$v.c ] && a=exercise_$${n}_answer_$$(echo $$v | tr - _); \
	  printf '    { "%s", "%s", %s, %s },\n' $$n $$v $$s $$a; done >> $@
	@printf '    { NULL, NULL, NULL, NULL },\n};\n' >> $@
$(B)/obj/exercise-variants.o: $(B)/exercise-variants.c | $(FIRST) ; @$(CC_ALL) -c $< -o $@
# The student's object is compiled every time (FILE may be another file),
# so it keeps no dependency file that could name a FILE since deleted.
$(B)/exercise/student-$(LESSON).o: FORCE | $(FIRST)
	@test -n "$(EX_LESSON)" || { echo "LESSON=$(LESSON): no lessons/$(LESSON)-* (LESSON=01 .. $(call nn,$(lastword $(LESSONS))/x))"; exit 2; }
	@test -f "$(FILE)" || { echo "FILE=$(FILE): no such file$(if $(VARIANT),; lesson $(LESSON)'s graded variants: $(or $(patsubst $(EX_LESSON)/exercise-%.c,%,$(wildcard $(EX_LESSON)/exercise-*.c)),none))"; exit 2; }
	@mkdir -p $(@D) && rm -f $(@:.o=.d) && $(filter-out -MMD -MP,$(CC_ALL)) $(STUDENT) -I$(EX_LESSON) -c $(FILE) -o $@
$(B)/obj/main-exercise-$(LESSON).o: src/exercise/main.c | $(FIRST) ; @mkdir -p $(@D) && $(CC_ALL) -DLESSON=lesson_$(LESSON) -c $< -o $@
$(B)/exercise-$(LESSON): $(B)/obj/main-exercise-$(LESSON).o $(B)/exercise/student-$(LESSON).o $(B)/obj/lessons.o $(ALL_LES) $(B)/libtristep.a
	@$(LD_ALL) $^ $(LIBS) -o $@
exercise: $(B)/exercise-$(LESSON) ; $< --file $(FILE) $(EX_VARIANT) $(if $(SCENE),--scene $(SCENE)) $(if $(STEP),--step $(STEP)) $(if $(SAMPLES),--samples $(SAMPLES))

# The judge and the runner (src/exercise/wire.h says what they say): make
# check and make grade compile the student's file against the student
# library of its lesson alone, $(B)/student/NN/ (src/exercise/student-library.txt
# says what each lesson's holds and why), into a runner; the judge,
# $(B)/judge-NN, which never links student code, sends it scenes and
# decides. The library: its objects compiled apart (each function in a
# section of its own, so the final link drops what nothing calls), made
# one object whose only global symbols are those the table lists; its
# headers copied into include/ (what lessons/NN-name/answer.c includes,
# shade.h, which every lesson's whole rasterizer may use, and the
# lesson's forbid.h).
SL_TABLE := src/exercise/student-library.txt
sl_col    = $(shell awk -v n=$1 -v c=$2 '$$1 == n || $$1 == "all" { for (i = 2; i <= NF; i++) if ($$i ~ "^" c ":") { sub("^" c ":", "", $$i); printf "%s ", $$i } }' $(SL_TABLE))
# (never with the sanitizers: a runner runs under make grade's memory limit,
# which their shadow memory does not fit; the judge is what they check)
SL_BASE   = $(CC) $(CFLAGS) -std=c17 -Wall -Wextra -pedantic -pthread $(TS_PORT) -DTRISTEP_NARRATE
$(B)/student/obj/%.o: %.c $(B)/cc.flag | $(FIRST) ; @mkdir -p $(@D) && $(SL_BASE) -MMD -MP -Isrc $(PKG_CFLAGS) -ffunction-sections -fdata-sections -c $< -o $@
# kept: make would drop them as intermediate
.PRECIOUS: $(B)/student/obj/%.o $(B)/student/%/library.o $(B)/student/%/include.stamp
sl_objs   = $(patsubst %.c,$(B)/student/obj/%.o,$(call sl_col,$1,file))
$(B)/student/%/library.o: $(SL_TABLE) $$(call sl_objs,$$*)
	@mkdir -p $(@D) && printf '%s\n' main $(call sl_col,$*,call) > $(@D)/allowed.txt
	@ld -r -o $@.tmp $(filter %.o,$^) && objcopy --keep-global-symbols=$(@D)/allowed.txt $@.tmp $@ && rm -f $@.tmp
$(B)/student/%/include.stamp: $(SL_TABLE) $$(wildcard lessons/$$*-*/exercise.c) src/exercise/student.h $(wildcard src/*.h src/*/*.h lessons/*/*.h)
	@rm -rf $(@D)/include && mkdir -p $(@D)/include && a=$$(ls lessons/$*-*/exercise.c) && loc= && \
	  for h in $$({ $(CC) -std=c17 -Isrc $(PKG_CFLAGS) $(STUDENT) -I$$(dirname $$a) -MM -MT x $$a; \
	               printf '#include "shade/shade.h"\n' | $(CC) -std=c17 -Isrc $(PKG_CFLAGS) -MM -MT x -x c -; } | \
	             tr -d '\\' | tr ' ' '\n' | grep '\.h$$' | grep -v '^/' | sort -u); do \
	    case $$h in src/*) d=$(@D)/include/$${h#src/} ;; *) d=$(@D)/include/$$(basename $$h); loc="$$loc $$(basename $$h)" ;; esac; \
	    mkdir -p $$(dirname $$d) && cp $$h $$d; done && \
	  { echo '/* forbid.h - what lesson $*'"'"'s exercise may not use of the headers (src/exercise/student-library.txt) */'; \
	    for l in $$loc; do printf '#include "%s"   /* first: its names are poisoned after it */\n' $$l; done; \
	    for w in $(call sl_col,$*,poison); do printf '#undef %s\n#pragma GCC poison %s\n' $$w $$w; done; } > $(@D)/include/forbid.h && touch $@
# the student's file, compiled as the runner's: the library's headers only,
# from a copy in a folder of its own (a quoted #include finds nothing beside
# it, as in make grade's sandbox), #line keeping its name in the messages
SL_CC     = $(SL_BASE) \
            -I$(B)/student/$(LESSON)/include -include exercise/student.h -include forbid.h
$(B)/student/$(LESSON)/file.o: FORCE $(B)/student/$(LESSON)/include.stamp | $(FIRST)
	@test -n "$(EX_LESSON)" || { echo "LESSON=$(LESSON): no lessons/$(LESSON)-* (LESSON=01 .. $(call nn,$(lastword $(LESSONS))/x))"; exit 2; }
	@test -f "$(FILE)" || { echo "FILE=$(FILE): no such file"; exit 2; }
	@mkdir -p $(@D)/src && { printf '#line 1 "%s"\n' "$$(printf '%s' '$(FILE)' | sed 's/[\\"]/\\&/g')"; cat '$(FILE)'; } > $(@D)/src/exercise.c && \
	  $(SL_CC) -c $(@D)/src/exercise.c -o $@
$(B)/student/$(LESSON)/runner: $(B)/student/$(LESSON)/file.o $(B)/student/$(LESSON)/library.o
	@for f in $(call sl_col,$(LESSON),need); do nm --defined-only $< | grep -q " T $$f$$" || \
	  { echo "your file defines no $$f(), the function lesson $(LESSON)'s exercise is (src/exercise/student-library.txt)"; exit 1; }; done
	@$(CC) $(LDFLAGS) -Wl,--gc-sections $^ -lm -pthread -o $@ 2> $@.log || { sh src/exercise/unlinked.sh $(LESSON) < $@.log; exit 1; }
$(B)/obj/judge-%.o: src/exercise/main.c | $(FIRST) ; @mkdir -p $(@D) && $(CC_ALL) -DLESSON=lesson_$* -DEXERCISE_JUDGE -c $< -o $@
$(B)/judge-%: $(B)/obj/judge-%.o $(B)/obj/lessons.o $(ALL_LES) $(B)/libtristep.a
	@$(LD_ALL) $^ $(LIBS) -o $@
check: $(B)/judge-$(LESSON) $(B)/student/$(LESSON)/runner
	@$< --check --runner $(B)/student/$(LESSON)/runner --log $(B)/student/$(LESSON)/log.txt $(if $(SEED),--seed $(SEED)) $(if $(SEARCH),--search $(SEARCH)) --file $(FILE) $(EX_VARIANT) --out $(B)/check --open 'make exercise LESSON=$(LESSON)$(if $(VARIANT), VARIANT=$(VARIANT))$(if $(filter command line,$(origin FILE)), FILE=$(FILE))' $(foreach s,$(SCENE),--check-scene $(s))

# make grade LESSON=NN DIR=folder [TIMEOUT=s] [CSV=file] [OUT=folder] [SEED=n]
# [POINTS=file] [UNSAFE=1]: every submission of the folder compiled, linked
# and checked in a sandbox of its own by the judge (src/exercise/grade.h),
# one CSV row each, a results.json each in OUT/<folder>/.
TIMEOUT  ?= 60
OUT      ?= $(B)/grade/$(LESSON)
CSV      ?= $(OUT).csv
GRADER   := $(shell git rev-parse HEAD 2>/dev/null || cat gradescope.commit 2>/dev/null || echo unknown)
grade: $(B)/judge-$(LESSON) $(B)/student/$(LESSON)/library.o $(B)/student/$(LESSON)/include.stamp
	@test -n "$(EX_LESSON)" || { echo "LESSON=$(LESSON): no lessons/$(LESSON)-*"; exit 2; }
	@test -n "$(DIR)" || { echo "make grade LESSON=NN DIR=folder: DIR is missing"; exit 2; }
	@$(if $(UNSAFE),,sh src/deps.sh grade &&) mkdir -p '$(dir $(CSV))' && $< --grade --dir '$(DIR)' --lib $(B)/student/$(LESSON) --out '$(OUT)' \
	  --csv '$(CSV)' --timeout $(TIMEOUT) --commit $(GRADER) --cc '$(CC)' $(if $(SEED),--seed '$(SEED)') \
	  $(if $(POINTS),--points '$(POINTS)') $(if $(ONE),--one) $(if $(UNSAFE),--unsafe) $(EX_VARIANT)

# make grade-hostile [HOSTILE="02 06 09"]: make grade on every hostile file
# of tests/test_grade.c (a fork bomb, 4 GiB, a flood of output, a file that
# includes itself, a destructor that forges, a full disk, ...) beside honest
# ones, for each lesson of the list: the long version of make test's share.
HOSTILE  ?= 02 06 09
grade-hostile: $(B)/tristep-tests   # (each make grade builds its lesson's judge)
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp TRISTEP_BUILD=$(B) TRISTEP_HOSTILE='$(HOSTILE)' $(B)/tristep-tests --filter 'grade/hostile_files'

grade-build: $(B)/judge-$(LESSON) $(B)/student/$(LESSON)/library.o $(B)/student/$(LESSON)/include.stamp

# make gradescope LESSON=NN [SEED=n] [POINTS=file]: an autograder zip for
# Gradescope, $(B)/gradescope-NN.zip: setup.sh and run_autograder
# (src/exercise/gradescope/) beside the repository's committed source, all
# at the zip's top (Gradescope unpacks it into /autograder/source), whose
# run_autograder grades /autograder/submission as make grade does (ONE=1:
# it is one student's folder) into /autograder/results/results.json.
gradescope:
	@test -n "$(EX_LESSON)" || { echo "LESSON=$(LESSON): no lessons/$(LESSON)-*"; exit 2; }
	@g=$(B)/gradescope-$(LESSON) && rm -rf $$g && mkdir -p $$g && git archive HEAD | tar -x -C $$g && \
	  for f in setup.sh run_autograder; do sed 's/@LESSON@/$(LESSON)/g' src/exercise/gradescope/$$f > $$g/$$f; chmod +x $$g/$$f; done && \
	  printf '%s\n' "$(if $(SEED),SEED=$(SEED)) $(if $(POINTS),POINTS=points.txt)" > $$g/gradescope.options && \
	  git rev-parse HEAD > $$g/gradescope.commit && \
	  $(if $(POINTS),cp '$(POINTS)' $$g/points.txt &&) \
	  rm -f $$g.zip && (cd $$g && zip -qr ../$$(basename $$g).zip .) && \
	  echo "gradescope: $$g.zip (setup.sh, run_autograder and the source at $$(git rev-parse --short HEAD), at the zip's top as Gradescope wants)"

# A student kit: this tree without what gives the answers away (src/kit.sh
# says what), in KIT; make run, exercise, check and test work there.
KIT      ?= $(B)/student-kit
student-kit: ; @sh src/kit.sh write '$(KIT)' $(NEED_ANSWERS)
# The long version of tests/test_kit.c: a whole kit built from nothing in
# $(KT)/kit, outside this tree; make check there on every lesson's worked
# answer and graded variant's, brought in from outside it (each passes),
# and on the kit's skeletons (each fails); then the kit's own make test.
KT       ?= $(or $(TMPDIR),/tmp)/tristep-kit-test
student-kit-test:
	@rm -rf $(KT) && $(MAKE) --no-print-directory student-kit KIT=$(KT)/kit
	@for a in $(wildcard lessons/*/answer.c lessons/*/answer-*.c); do n=$$(basename $$(dirname $$a) | cut -c1-2); \
	  v=$$(basename $$a .c | sed -n 's/^answer-//p'); f=$(KT)/$$n$${v:+-$$v}.c; cp $$a $$f; \
	  $(MAKE) -C $(KT)/kit --no-print-directory -s check LESSON=$$n $${v:+VARIANT=$$v} FILE=$$f > $$f.txt 2>&1 \
	    || { cat $$f.txt; echo "student-kit-test: $$a fails in the kit"; exit 1; }; \
	  ! $(MAKE) -C $(KT)/kit --no-print-directory -s check LESSON=$$n $${v:+VARIANT=$$v} > $$f.skeleton.txt 2>&1 \
	    || { echo "student-kit-test: the kit's skeleton of $$a passes"; exit 1; }; \
	  echo "student-kit-test: $$a passes in the kit, its skeleton fails"; done
	$(MAKE) -C $(KT)/kit --no-print-directory test
# Without the answers the tests are compiled with TRISTEP_NO_ANSWERS, again
# when the answers come or go (answers.flag); the rest of the build, and
# cc.flag, do not change.
$(B)/answers.flag: FORCE | $(B)/config.mk ; @echo '$(ANSWERS_HERE)' | cmp -s - $@ || echo '$(ANSWERS_HERE)' > $@
$(B)/obj/tests/%.o: tests/%.c $(B)/cc.flag $(B)/answers.flag | $(FIRST)
	@mkdir -p $(@D) && $(CC_ALL) $(if $(ANSWERS_HERE),,-DTRISTEP_NO_ANSWERS) -DTRISTEP_NARRATE -c $< -o $@

run: $(B)/$(filter $(LESSON)-%,$(LESSONS)) ; $<
test: deps-test all $(B)/tristep-tests $(B)/tristep-bench $(B)/lines-peer $(B)/tsan-tiles $(B)/tristep-soak $(B)/judge-02 $(B)/student/02/library.o $(B)/student/02/include.stamp
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp TRISTEP_BUILD=$(B) $(B)/tristep-tests --jobs=2
	$(if $(and $(ANSWERS_HERE),$(if $(wildcard tests/left-out.txt),,1)),,@sh src/kit.sh left-out $(NEED_ANSWERS))
	@$(MAKE) --no-print-directory SANITIZE=1 $(BUILD)/sanitize/fuzz-replay
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 $(BUILD)/sanitize/fuzz-replay tests/fuzz/corpus
	@$(MAKE) --no-print-directory aarch64 simde-test
bench: deps-bench all
	@$(MAKE) --no-print-directory $(B)/tristep-bench   # read again: deps-bench may have installed OSMesa
	$(B)/tristep-bench --out $(B) --markdown tests/bench/BENCH.md --figures-cmd '$(MAKE) --no-print-directory -s BUILD=$(BUILD) FIGURES=$(B)/bench-figures figures'
# The README's two commands on a brand-new Debian 12 (tests/fresh/fresh-test.sh; root).
fresh-test: ; @bash tests/fresh/fresh-test.sh
MINUTES  ?= 10
soak: deps-test
	@$(MAKE) --no-print-directory SANITIZE=1 all $(BUILD)/sanitize/tristep-soak
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp $(BUILD)/sanitize/tristep-soak --build $(BUILD)/sanitize --minutes $(MINUTES)
# Every figure of figures/list into $(FIGURES), one process each (cairo's SVG ids count per process).
FIGURES  ?= figures
figures: all ; @mkdir -p $(FIGURES) && sh figures/make-figures.sh $(B) $(FIGURES)
clean: ; rm -rf $(BUILD)

# The dependencies of the objects the build keeps (not those of a student's
# or a graded file, which may be gone).
-include $(shell find $(B)/obj $(B)/fast $(B)/mutations -name '*.d' 2>/dev/null)
