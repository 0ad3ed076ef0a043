# SPDX-License-Identifier: MIT
# pt: a portable wavefront path tracer in C11 + OpenCL C 1.2.
#   make          build build/pt              make run    install deps, build, render the default scene
#   make test     build and run every test    make asan   build with address+undefined sanitizers
#   make bench    run the benchmark suites    make clean
#   make fuzz-replay  replay the malformed-input corpus under ASan+UBSan (part of make test)
#   make fuzz FUZZ_SECONDS=N   coverage-guided fuzzing with libFuzzer (needs clang), N s per target
# Variables: OPT (optimisation flags), V=1 (show commands), SCENE, DEVICE.

CC      ?= cc
CXX     ?= c++
OPT     ?= -O2 -g
BUILD   ?= build
PKGS    := OpenCL libcjson glfw3 gl tinyobjloader expat libxml-2.0 assimp
CPPFLAGS += -Ihost -I$(BUILD) -I/usr/include/OpenEXR -I/usr/include/Imath -I/usr/include/stb \
            $(shell pkg-config --cflags-only-I $(PKGS) 2>/dev/null) -D_POSIX_C_SOURCE=200809L -DCL_TARGET_OPENCL_VERSION=120
CFLAGS  += -std=c11 -Wall -Wextra -Wpedantic $(OPT) -MMD -MP
CXXFLAGS += -std=c++11 -Wall -Wextra $(OPT) -MMD -MP
# bin/pt finds the libraries of a relocatable bundle (make bundle) in ../lib.
# DT_RPATH rather than RUNPATH (--disable-new-dtags): it also applies to the libraries' own
# dependencies (libGL.so.1 -> libGLdispatch.so.0), which a RUNPATH would leave to the system.
LDFLAGS += -Wl,-rpath,'$$ORIGIN/../lib' -Wl,--disable-new-dtags
LDLIBS  += $(shell pkg-config --libs $(PKGS) 2>/dev/null) -lOpenEXRCore-3_1 -ltinygltf -lm -lpthread
# libdraco (glTF KHR_draco_mesh_compression, io/gltf_draco.cc) statically: Debian's libdraco.so
# exports its own build of tinygltf, whose symbols would replace libtinygltf's (another layout:
# a crash in TinyGLTF's destructor); from the archive only the decoder's objects are linked.
LDLIBS  += -Wl,-Bstatic -ldraco -Wl,-Bdynamic
# MPI (OpenMPI: libopenmpi-dev): always linked, started only under mpirun (host/dist/mpi_link.h).
MPI_CFLAGS := $(shell mpicc --showme:compile 2>/dev/null || pkg-config --cflags ompi-c 2>/dev/null)
MPI_LIBS   := $(shell mpicc --showme:link 2>/dev/null || pkg-config --libs ompi-c 2>/dev/null)
CPPFLAGS += $(MPI_CFLAGS)
LDLIBS   += $(MPI_LIBS)
TEST_LDLIBS := -lcriterion

ifeq ($(V),1)
Q :=
else
Q := @
endif

# The OpenCL program, in the order it is assembled (shared.h first: both compilers read it).
CL_SOURCES := cl/shared.h cl/shared/features.h cl/shared/program_parts.h cl/shared/geometry.h cl/shared/material.h cl/shared/medium.h cl/shared/render.h \
              cl/core/util.cl cl/core/sobol.cl cl/core/rng.cl cl/core/sampling.cl cl/core/camera.cl \
              cl/geometry/intersect_triangle.cl cl/geometry/instance.cl cl/geometry/box_test.cl \
              cl/geometry/bvh_node_2wide.cl cl/geometry/bvh_traverse.cl \
              cl/geometry/bvh_traverse_speculative.cl cl/geometry/bvh_traverse_wide.cl \
              cl/geometry/bvh_query.cl cl/geometry/bvh_traverse_packet.cl \
              cl/geometry/scene_trace.cl \
              cl/geometry/ray_offset.cl cl/geometry/surface.cl cl/material/texture.cl \
              cl/material/bsdf_common.cl cl/material/surface_detail.cl cl/material/microfacet.cl cl/material/diffuse.cl \
              cl/material/conductor.cl cl/material/dielectric.cl cl/material/principled.cl \
              cl/material/bsdf.cl cl/material/shading_point.cl \
              cl/medium/phase.cl cl/medium/medium_grid.cl cl/medium/medium_track.cl cl/medium/medium_boundary.cl cl/light/light_env.cl cl/light/light_analytic.cl cl/light/light_sample.cl \
              cl/light/accretion_disk.cl \
              cl/parallel/scan.cl cl/parallel/sort_materials.cl cl/post/bloom.cl \
              cl/stages/path_state.cl cl/stages/render_aov.cl cl/stages/generate_camera_rays.cl \
              cl/stages/intersect_closest.cl cl/stages/shade_emission.cl \
              cl/stages/shade_next_event.cl cl/stages/intersect_shadow.cl cl/stages/shade_surface.cl \
              cl/stages/integrate_geodesic.cl cl/stages/megakernel.cl \
              cl/stages/accumulate_film.cl cl/stages/film_variance.cl cl/stages/adaptive_select.cl

HOST_C   := $(wildcard host/*/*.c)
HOST_CXX := $(wildcard host/*/*.cc)
LIB_OBJS := $(HOST_C:host/%.c=$(BUILD)/host/%.o) $(HOST_CXX:host/%.cc=$(BUILD)/host/%.o) \
            $(BUILD)/kernel_source.o
TESTS    := $(patsubst tests/%.c,$(BUILD)/tests/%,$(wildcard tests/test_*.c))
TEST_SUPPORT := $(BUILD)/tests/support.o

SCENE   ?= scenes/cornell-box
DEVICE  ?=

.PHONY: all run test asan bench clean deps references bundle fuzz fuzz-replay
all: $(BUILD)/pt

deps:
	$(Q)./tools/install-deps.sh

run: deps
	$(Q)$(MAKE) --no-print-directory all
	$(BUILD)/pt render $(SCENE) $(if $(DEVICE),--device $(DEVICE))

# The tests run again under every other BVH layout (make test).
BVH_LAYOUT_TESTS := $(addprefix $(BUILD)/tests/,test_accel_bvh_traverse test_accel_hit_ties \
                    test_accel_instances_bvh)

test: deps
	$(Q)./tools/check-layers.sh
	$(Q)$(MAKE) --no-print-directory all $(TESTS)
	$(Q)PT_BIN=$(BUILD)/pt ./tools/run-tests.sh $(TESTS) \
	    PT_BVH_WIDTH=4 $(BVH_LAYOUT_TESTS) PT_BVH_WIDTH=2 $(BVH_LAYOUT_TESTS) \
	    PT_BVH_WIDTH=2 PT_BVH_QUANTIZED=1 $(BVH_LAYOUT_TESTS)
	$(Q)$(MAKE) --no-print-directory fuzz-replay

asan:
	$(Q)$(MAKE) --no-print-directory BUILD=build-asan OPT="-O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer" \
	    LDFLAGS="-fsanitize=address,undefined" all

# The malformed-input corpus (tests/fuzz/gen_corpus.py), replayed on the ASan+UBSan binary: every
# case must end in exit 0 or one "pt: ..." line, within FUZZ_TIMEOUT s (a true hang; far above a healthy case under load) and 3 GiB (tests/fuzz/replay.py).
FUZZ_TIMEOUT ?= 300
fuzz-replay: asan
	$(Q)python3 tests/fuzz/gen_corpus.py build-asan/fuzz >/dev/null
	$(Q)python3 tests/fuzz/replay.py build-asan/pt build-asan/fuzz -j 2 --timeout $(FUZZ_TIMEOUT)

# libFuzzer targets (tests/fuzz/fuzz_*.c) for the scene parser, the OBJ/MTL loader, the PLY reader, the glTF import,
# the texture loader, the checkpoint reader and the pbrt-v4 importer, built with clang (apt-get install clang) into build-fuzz/; each runs
# FUZZ_SECONDS s from the corpus's inputs as seeds. Findings (crash-*, timeout-*, oom-*) land in build-fuzz/findings/.
FUZZ_SECONDS ?= 60
FUZZ_CC ?= clang
FUZZ_TARGETS := scene obj texture ply gltf checkpoint pbrt mitsuba collada assimp volume
fuzz:
	$(Q)command -v $(FUZZ_CC) >/dev/null || { echo "make fuzz needs clang: apt-get install clang"; exit 1; }
	$(Q)$(MAKE) --no-print-directory BUILD=build-fuzz CC=$(FUZZ_CC) CXX=$(FUZZ_CC)++ \
	    OPT="-O1 -g -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer" \
	    $(FUZZ_TARGETS:%=build-fuzz/fuzz_%)
	$(Q)python3 tests/fuzz/gen_corpus.py build-fuzz/replay --seeds build-fuzz/seeds >/dev/null
	$(Q)mkdir -p build-fuzz/findings
	$(Q)for t in $(FUZZ_TARGETS); do mkdir -p build-fuzz/corpus/$$t; echo "== fuzz_$$t"; \
	    ASAN_OPTIONS=detect_leaks=0 nice build-fuzz/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) \
	        -rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10 -max_len=65536 -print_final_stats=1 \
	        -artifact_prefix=build-fuzz/findings/$$t- build-fuzz/corpus/$$t build-fuzz/seeds/$$t \
	        2>&1 | grep -E '^(#[0-9]+ +DONE|Done|stat::|==[0-9]+==ERROR|SUMMARY|artifact_prefix|Test unit written)' \
	        || true; echo "fuzz_$$t: corpus of $$(ls build-fuzz/corpus/$$t | wc -l) inputs" \
	        "(+ $$(ls build-fuzz/seeds/$$t | wc -l) seeds)"; done
	$(Q)ls build-fuzz/findings | sed 's/^/finding: /'; echo "fuzz: $$(ls build-fuzz/findings | wc -l) findings"

build-fuzz/fuzz_%: tests/fuzz/fuzz_%.c tests/fuzz/fuzz_input.h build-fuzz/libpt.a
	@echo "  LD    $@"
	$(Q)$(CXX) $(CPPFLAGS) -Itests/fuzz -std=c11 -w $(OPT) -x c $< -x none -fsanitize=fuzzer \
	    -o $@ build-fuzz/libpt.a $(LDLIBS)

bench: all
	$(Q)PT=$(BUILD)/pt ./tools/bench.sh $(if $(DEVICE),--device $(DEVICE))

# Re-renders tests/references/ with Mitsuba 3 (slow; only when asked, never as a dependency).
references: ; ./tools/make-references.sh

# The test scenes' large generated meshes (tools/make_material_scenes.py GENERATED_MESHES; not in
# git): written before any test binary, byte for byte the meshes the references were made from.
TEST_MESHES := $(foreach s,conductors envmap envmap-diffuse glass glass-clear mix,tests/scenes/$(s)/$(s).obj)
$(BUILD)/test-meshes.stamp: tools/make_material_scenes.py tools/make_test_scenes.py
	@mkdir -p $(@D)
	@echo "  GEN   $(TEST_MESHES)"
	$(Q)python3 tools/make_material_scenes.py tests/scenes
	$(Q)touch $@
$(TESTS): $(BUILD)/test-meshes.stamp
# The media scenes' generated meshes, grid (.vol) and sky (tools/make_media_scenes.py GENERATED; not in git).
$(BUILD)/test-media.stamp: tools/make_media_scenes.py tools/make_material_scenes.py tools/make_test_scenes.py tools/mitsuba_vol.py
	@mkdir -p $(@D)
	@echo "  GEN   tests/scenes/{fog-room,smoke,liquid,subsurface}"
	$(Q)python3 tools/make_media_scenes.py tests/scenes
	$(Q)touch $@
$(TESTS): $(BUILD)/test-media.stamp
# The reference scenes as Mitsuba 3 XML (tools/mitsuba_xml.py; not in git), for test_reference.
MITSUBA_XML_SCENES := furnace cornell cornell-sphere textured conductors glass-clear normalmap mix
MITSUBA_XML_SCENES += fog-room liquid subsurface
$(BUILD)/mitsuba-xml.stamp: tools/mitsuba_xml.py tools/mitsuba_reference.py tools/mitsuba_materials.py \
                            tools/mitsuba_obj.py $(BUILD)/test-meshes.stamp
	@echo "  GEN   tests/scenes/*/mitsuba/scene.xml"
	$(Q)python3 tools/mitsuba_xml.py $(foreach s,$(MITSUBA_XML_SCENES),tests/scenes/$(s) tests/scenes/$(s)/mitsuba)
	$(Q)touch $@
$(BUILD)/tests/test_reference: $(BUILD)/mitsuba-xml.stamp
$(BUILD)/mitsuba-xml.stamp: $(BUILD)/test-media.stamp tools/mitsuba_media.py tools/mitsuba_lights.py

VERSION ?= $(shell git describe --always --dirty 2>/dev/null || echo dev)
bundle: all $(patsubst tools/%.c,$(BUILD)/tools/%,$(wildcard tools/bench_*.c))
	$(Q)./tools/bundle.sh $(BUILD) $(VERSION)

clean:
	rm -rf build build-asan build-fuzz dist

$(BUILD)/pt: $(BUILD)/host/main.o $(BUILD)/libpt.a
	@echo "  LD    $@"
	$(Q)$(CXX) $(LDFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/libpt.a: $(LIB_OBJS)
	$(Q)rm -f $@ && ar rcs $@ $^

$(BUILD)/kernel_source.c: $(CL_SOURCES) tools/embed-cl.sh Makefile
	@mkdir -p $(@D)
	@echo "  EMBED $@"
	$(Q)./tools/embed-cl.sh $@ $(CL_SOURCES)

$(BUILD)/%.o: $(BUILD)/%.c
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/host/%.o: host/%.c
	@mkdir -p $(@D)
	@echo "  CC    $<"
	$(Q)$(CC) $(CPPFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/host/%.o: host/%.cc
	@mkdir -p $(@D)
	@echo "  CXX   $<"
	$(Q)$(CXX) $(CPPFLAGS) $(CXXFLAGS) -c -o $@ $<

$(BUILD)/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	@echo "  CC    $<"
	$(Q)$(CC) $(CPPFLAGS) -Itests $(CFLAGS) -c -o $@ $<

$(BUILD)/tests/%.o: tests/%.cc
	@mkdir -p $(@D)
	@echo "  CXX   $<"
	$(Q)$(CXX) $(CPPFLAGS) -Itests $(CXXFLAGS) -c -o $@ $<

$(BUILD)/tests/test_%: $(BUILD)/tests/test_%.o $(TEST_SUPPORT) $(BUILD)/libpt.a
	@echo "  LD    $@"
	$(Q)$(CXX) $(LDFLAGS) -o $@ $^ $(LDLIBS) $(TEST_LDLIBS)

# The BVH tests share tests/bvh_fixtures*.c (bvh_fixtures.h).
$(filter $(BUILD)/tests/test_accel_bvh_%,$(TESTS)): $(patsubst tests/%.c,$(BUILD)/tests/%.o,$(wildcard tests/bvh_fixtures*.c))
# The 'pt' end-to-end tests share tests/cli_run.c.
$(BUILD)/tests/test_cli $(BUILD)/tests/test_cli_options $(BUILD)/tests/test_checkpoint: $(BUILD)/tests/cli_run.o
$(BUILD)/tests/test_multi_device: $(BUILD)/tests/cli_run.o
$(BUILD)/tests/test_io_ply $(BUILD)/tests/test_io_ply_bad_input: $(BUILD)/tests/ply_fixtures.o
# The Draco tests write their glTF twins with libdraco's encoder (tests/draco_fixture.cc).
$(BUILD)/tests/test_gltf_draco: $(BUILD)/tests/draco_fixture.o
$(BUILD)/tests/test_denoise: $(BUILD)/tests/cli_run.o
$(BUILD)/tests/test_viewer_denoise: $(BUILD)/tests/viewer_session.o
$(BUILD)/tests/test_stop_matrix $(BUILD)/tests/test_checkpoint_faults: $(BUILD)/tests/cli_run.o
# The 'pt view' end-to-end tests share tests/viewer_session.c.
$(BUILD)/tests/test_viewer $(BUILD)/tests/test_viewer_film $(BUILD)/tests/test_viewer_post: \
    $(BUILD)/tests/viewer_session.o

# Tools: one binary per tools/NAME.c, linked like the tests but without Criterion (they may share
# the tests' header-only helpers, hence -Itests).
.PHONY: tools bench-bvh bench-tlas
tools: $(patsubst tools/%.c,$(BUILD)/tools/%,$(wildcard tools/*.c))

bench-bvh: $(BUILD)/tools/bench_bvh
	$(Q)$(BUILD)/tools/bench_bvh $(if $(DEVICE),--device $(DEVICE)) && python3 tools/bench_bvh.py

bench-tlas: $(BUILD)/tools/bench_tlas
	$(Q)$(BUILD)/tools/bench_tlas

$(BUILD)/tools/%.o: tools/%.c
	@mkdir -p $(@D)
	@echo "  CC    $<"
	$(Q)$(CC) $(CPPFLAGS) -Itests $(CFLAGS) -c -o $@ $<

$(BUILD)/tools/%: $(BUILD)/tools/%.o $(BUILD)/libpt.a
	@echo "  LD    $@"
	$(Q)$(CXX) $(LDFLAGS) -o $@ $^ $(LDLIBS)

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
# NanoVDB (io/volume_nvdb*.cc, header-only) needs C++17.
$(BUILD)/host/io/volume_nvdb.o $(BUILD)/host/io/volume_nvdb_grid.o: CXXFLAGS += -std=c++17
# The grid reader tests write their NanoVDB files with NanoVDB's own builder (tests/nvdb_fixture.cc).
$(BUILD)/tests/test_volume_nvdb: $(BUILD)/tests/nvdb_fixture.o
$(BUILD)/tests/nvdb_fixture.o: CXXFLAGS += -std=c++17
$(BUILD)/tests/test_media_scene_nvdb $(BUILD)/tests/test_media_grid: $(BUILD)/tests/nvdb_fixture.o
