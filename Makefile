# rt -- a teaching ray tracer. `make` builds ./ray (double) and ./ray_float (float);
# `make test` runs every test; `make starter` writes the student kit; `make grade` grades a
# tracer; `make bench` measures speed and accuracy into build/bench/ (and `make bench-publish`
# copies a run into docs/bench/); `make sanitize` runs the tests under
# AddressSanitizer and UndefinedBehaviorSanitizer; `make clean` removes every product.

# Parallel by default: one job a core, unless -j was given. (GNU make 4; the make 3.81 of macOS
# takes `make -j4` instead.)
JOBS := $(shell getconf _NPROCESSORS_ONLN 2>/dev/null || echo 2)
ifeq ($(filter -j%,$(MAKEFLAGS)),)
MAKEFLAGS += -j$(JOBS)
endif

CXX ?= g++
# (No -g: debug information takes a third of the build's time. For a debugger,
# `make CXXFLAGS="-O0 -g"`; build/config then rebuilds everything.)
CXXFLAGS ?= -O3
# Required flags, kept apart so CXXFLAGS stays the user's. -ffp-contract=off: a fused
# multiply-add changes how a*b - c*d rounds, which breaks the watertight triangle test (and makes
# images differ between machines); rt wants the arithmetic exactly as written.
RT_FLAGS = -std=c++17 -Wall -Wextra -ffp-contract=off -fno-math-errno -pthread -MMD -MP
# `make RT_SCALAR=1`: fast/'s kernels as plain scalar code, no vector extensions (fast/lanes.h).
ifneq ($(RT_SCALAR),)
RT_FLAGS += -DRT_SCALAR
endif

# What every product was built with; when it changes (another CXX, CXXFLAGS or RT_SCALAR),
# build/config changes, and everything is built again.
CONFIG = $(CXX) $(CXXFLAGS) $(RT_FLAGS)
$(shell mkdir -p build && echo '$(CONFIG)' | cmp -s - build/config || echo '$(CONFIG)' >build/config)

# (A cross-build points pkg-config at the target's libraries with PKG_CONFIG_LIBDIR: .ci/run.)
PNG_CFLAGS := $(shell pkg-config --cflags libpng 2>/dev/null)
PNG_LIBS := $(shell pkg-config --libs libpng 2>/dev/null || echo -lpng)

# The teaching core at the top (every scene_*.cpp is a scene built in C++: README, "Writing a
# scene in C++"), and the three wings: robust/, fast/ and app/.
SCENES = $(basename $(wildcard scene_*.cpp))
TOP = geometry camera blur shade path path_full render smooth $(SCENES)
ROBUST = robust/watertight robust/plane robust/rescale robust/leave
FAST = fast/commit fast/commit_tree fast/build fast/kernel fast/commit_spheres
APP = app/options app/modes app/image app/image_read app/text app/scene_file app/statements \
      app/mesh app/mesh_words app/mesh_normals app/probe app/views
CORE = $(TOP) $(ROBUST) $(FAST) $(APP)
TESTS = $(basename $(notdir $(wildcard tests/test_*.cpp))) exercise hard_cases hard_cases_offset robust_scenes
# The tests that run the program or read files, and use no `real`: compiled once for both builds.
SHARED_TESTS = test_program test_files test_corpus test_compare
PER_BUILD_TESTS = $(filter-out $(SHARED_TESTS),$(TESTS))

# Object lists for one build variant: $(call objs,DIR,NAMES)
objs = $(addprefix $(1)/,$(addsuffix .o,$(2)))

DOUBLE_CORE = $(call objs,build/double,$(CORE))
FLOAT_CORE = $(call objs,build/float,$(CORE))
SAN_CORE = $(call objs,build/sanitize,$(CORE))

all: ray ray_float

ray: build/double/ray.o $(DOUBLE_CORE)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

ray_float: build/float/ray.o $(FLOAT_CORE)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

build/double/%.o: %.cpp build/config
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) $(PNG_CFLAGS) -I. -c -o $@ $<

build/float/%.o: %.cpp build/config
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) $(PNG_CFLAGS) -DRT_FLOAT -I. -c -o $@ $<

# The test programs: the same tests, once in double and once in float (SHARED_TESTS in both).
build/shared/%.o: %.cpp build/config
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) $(PNG_CFLAGS) -I. -c -o $@ $<

SHARED_TEST_OBJS = $(call objs,build/shared/tests,$(SHARED_TESTS))
build/double/run_tests: $(call objs,build/double/tests,$(PER_BUILD_TESTS)) $(SHARED_TEST_OBJS) $(DOUBLE_CORE)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

build/float/run_tests: $(call objs,build/float/tests,$(PER_BUILD_TESTS)) $(SHARED_TEST_OBJS) $(FLOAT_CORE)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

# rt's images of every scene with the handouts' methods, the kit's references/ (make starter);
# defined before the first rule that names them, as make reads a rule's prerequisites at once.
REFERENCES = $(addprefix build/references/,$(addsuffix .png,$(notdir $(basename $(wildcard scenes/*.scene)))))
test: all build/double/run_tests build/float/run_tests build/tiny build/grader build/grade-set $(REFERENCES)
	@CXX="$(CXX)" sh tests/run.sh build/double/run_tests build/float/run_tests tests/recipe.sh \
	    tests/grade.sh tests/starter.sh tests/class.sh

check: test

# The checks of this build's own code, the test programs in double and float, without the kit's,
# the grader's and the class's suites (CI's clang build runs these and compares its images; the
# suites check scripts and a kit, which the first build has checked).
check-programs: all build/double/run_tests build/float/run_tests
	@sh tests/run.sh build/double/run_tests build/float/run_tests

# The student's quicker loop: the checks of the handouts' steps (hits, shading, the camera, the
# assignment image, the effects), in double only. `make test` stays the whole suite.
CORE_GROUPS = geometry triangles shading camera assignment_image effects
check-core: ray build/double/run_tests
	@build/double/run_tests $(CORE_GROUPS)

# Sanitizers: the core, the program and the double tests rebuilt with ASan + UBSan; the tests
# that run the program run the sanitized one.
SAN_FLAGS = -O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all

build/sanitize/%.o: %.cpp build/config
	@mkdir -p $(@D)
	$(CXX) $(SAN_FLAGS) $(RT_FLAGS) $(PNG_CFLAGS) -I. -c -o $@ $<

build/sanitize/ray: build/sanitize/ray.o $(SAN_CORE)
	$(CXX) $(SAN_FLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

build/sanitize/run_tests: $(call objs,build/sanitize/tests,$(TESTS)) $(SAN_CORE)
	$(CXX) $(SAN_FLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

# The sanitized checks run slowly, so one process a core shares out the groups (run_tests --claim).
SAN_RUNS = $(foreach k,$(shell seq $(JOBS)),"build/sanitize/run_tests --claim build/sanitize/claims")
sanitize: build/sanitize/ray build/sanitize/run_tests
	@rm -rf build/sanitize/claims && mkdir build/sanitize/claims
	@RAY=build/sanitize/ray sh tests/run.sh $(SAN_RUNS)

# Fuzzing (clang and libFuzzer): the scene reader and the probe-line reader, with ASan + UBSan.
# Runs FUZZ_SECONDS (default 600) starting from tests/corpus; inputs that crash are kept by
# libFuzzer as crash-* files, to be fixed and copied into tests/corpus.
FUZZ_CXX = clang++
FUZZ_FLAGS = -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all
FUZZ_SECONDS ?= 600

build/fuzz/%.o: %.cpp build/config
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(FUZZ_FLAGS) -fsanitize=fuzzer-no-link $(RT_FLAGS) $(PNG_CFLAGS) -I. -c -o $@ $<

build/fuzz/fuzz_scene: $(call objs,build/fuzz,$(CORE) tests/exercise tests/fuzz_scene)
	$(FUZZ_CXX) $(FUZZ_FLAGS) -fsanitize=fuzzer $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

fuzz: build/fuzz/fuzz_scene
	@mkdir -p build/fuzz/corpus
	build/fuzz/fuzz_scene -max_total_time=$(FUZZ_SECONDS) -max_len=4096 -timeout=10 \
	    -artifact_prefix=build/fuzz/ build/fuzz/corpus tests/corpus

# The benchmark programs: bench/bench.cpp and report.cpp with the core and the hard-case suite,
# once in double and once in float.
BENCH_OBJS = bench/bench bench/report bench/robustness bench/methods bench/layout bench/path bench/peers bench/terminator bench/svg tests/hard_cases tests/hard_cases_offset tests/robust_scenes

build/double/rtbench: $(call objs,build/double,$(BENCH_OBJS)) $(DOUBLE_CORE)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

build/float/rtbench: $(call objs,build/float,$(BENCH_OBJS)) $(FLOAT_CORE)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

# The speed baseline: a plain float student solution of the assignment (bench/student.cpp, not
# part of rt), built with exactly -O2, as the speed target states, not with CXXFLAGS.
build/student: bench/student.cpp
	@mkdir -p $(@D)
	$(CXX) -O2 -std=c++17 -o $@ $< $(PNG_CFLAGS) $(PNG_LIBS)

# make bench's peer rows (bench/peers.sh): rt's side in double and float (bench/peer_rt.cpp), and
# Embree 3 (bench/peer_embree.cpp), built only where Embree is installed (Debian's libembree-dev).
# (tinybvh and bvh v2, when given, are built by bench/peers.sh itself, under build/peers/.)
build/peer_rt: build/double/bench/peer_rt.o $(DOUBLE_CORE)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

build/peer_rt_float: build/float/bench/peer_rt.o $(FLOAT_CORE)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

build/peer_embree: bench/peer_embree.cpp bench/peers.h build/config
	$(CXX) $(CXXFLAGS) -std=c++17 -Wall -Wextra -o $@ bench/peer_embree.cpp -lembree3

bench: ray ray_float build/double/rtbench build/float/rtbench build/student build/make_mesh \
       build/weekend_scene build/peer_rt build/peer_rt_float
	@sh bench/bench.sh

# The student kit: build/starter/rt-starter and build/starter/rt-starter.tar.gz, rt's teaching core
# with the functions tools/starter/stubs.list names as stubs, and without robust/ and fast/
# (tools/starter.sh).
build/references/%.png: scenes/%.scene ray
	@mkdir -p $(@D)
	./ray $< --methods handout -o $@ >/dev/null

# The reading edition: build/reading/, the core without wings, every step solved, the handouts'
# methods only, building on its own (tools/starter/READING.md is its README).
reading:
	@sh tools/starter.sh build/reading --reading

starter: ray build/tiny build/grade-set $(REFERENCES)
	@HINTS="$(HINTS)" SEED="$(SEED)" sh tools/starter.sh build/starter

# The grader (tools/grade/, docs/teaching.md): build/grade-set writes a reference set (rt's images
# of the grading scenes, and those of build/tiny, a tiny tracer with a bug on demand:
# tests/grade/tiny.cpp); build/grader grades a tracer, a folder of images, or a class against it.
# `make grade TRACER=PROGRAM | IMAGES=DIR | CLASS=DIR [SEED=N] [TIME=S]` (tools/grade.sh).
GRADE_LIB = tools/grade/run tools/grade/judge tools/grade/grade tools/grade/report \
            tools/grade/build tools/grade/set_read
build/tiny: tests/grade/tiny.cpp build/config
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) -std=c++17 -Wall -Wextra -ffp-contract=off -o $@ $< $(PNG_CFLAGS) $(PNG_LIBS)

build/grader: $(call objs,build/double,tools/grade/main $(GRADE_LIB)) $(DOUBLE_CORE)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

build/grade-set: $(call objs,build/double,tools/grade/set tools/grade/scenes $(GRADE_LIB)) $(DOUBLE_CORE)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $^ $(PNG_LIBS)

# How the grader compiles a class's submissions: the kit's flags (warnings are the student's).
KIT_CXXFLAGS = -O2 -std=c++17 -w -ffp-contract=off -fno-math-errno -pthread $(PNG_CFLAGS)

grade: ray build/tiny build/grader build/grade-set
	@TRACER="$(TRACER)" IMAGES="$(IMAGES)" CLASS="$(CLASS)" SEED="$(SEED)" TIME="$(TIME)" \
	    REPORT="$(REPORT)" JSON="$(JSON)" KIT="$(KIT)" OUT="$(OUT)" CXX="$(CXX)" \
	    KIT_CXXFLAGS="$(KIT_CXXFLAGS)" PNG_LIBS="$(PNG_LIBS)" sh tools/grade.sh

# The mesh generator (tools/make_mesh.cpp), for trying the `mesh` statement on large models:
# `make build/make_mesh`. Not part of `make`: rt does not need it.
build/make_mesh: tools/make_mesh.cpp
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $<

# The writer of scenes/weekend.scene (tools/weekend_scene.cpp): Ray Tracing in One Weekend's final
# scene with the book's random numbers; make bench also checks it against the book's program.
build/weekend_scene: tools/weekend_scene.cpp
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(RT_FLAGS) -o $@ $<

# Publishing a bench run is a separate, deliberate step: copies build/bench's tables, plots and
# heat maps (not its reference renders) into docs/bench/, which the docs link to.
bench-publish:
	@test -f build/bench/speed.md || { echo "run make bench first"; exit 2; }
	@mkdir -p docs/bench
	cp build/bench/*.md build/bench/*.svg build/bench/*.csv docs/bench/
	for f in build/bench/*.png; do case $$f in */ref_*|*/base_*) ;; *) cp $$f docs/bench/ ;; esac; done

clean:
	rm -rf build ray ray_float

.PHONY: all test check check-core check-programs starter reading grade sanitize fuzz bench bench-publish clean

-include $(wildcard build/*/*.d build/*/*/*.d build/*/*/*/*.d)
