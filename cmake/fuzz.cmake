# The fuzz build (issue 20; scripts/test.sh builds it as build-fuzz with Debian's clang, -DSHADETWIN_FUZZ=ON): libFuzzer
# targets (fuzz/*.cpp) for the parsers of every input file the project reads, over only those sources (the shading
# dialect needs C++20 features clang 14 lacks; the parsers do not), with AddressSanitizer + UBSan. Included from
# CMakeLists.txt before anything else is built.
#
# Each target runs for a bounded time from its seed corpus (fuzz/make_seeds.sh: the shipped scenes, device descriptions,
# npm meshes, a glTF triangle and its binary twin, small EXR/HDR/PNG); what it finds goes to fuzz_<target>_corpus/ in
# the build folder and a crash to fuzz_<target>_crash-*, which becomes a regression input under
# fuzz/regressions/<target>/ (run, with every seed, by fuzz_<target>_inputs).
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "SHADETWIN_FUZZ needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++")
endif()
set(FUZZ_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g1 -O1)
add_library(fuzz_parsers STATIC src/scene/scene.cpp src/scene/mesh.cpp src/scene/tinygltf_impl.cpp src/util/image_io.cpp
            src/util/output_file.cpp src/model/device_desc.cpp)
target_include_directories(fuzz_parsers PUBLIC ${CMAKE_SOURCE_DIR} ${CMAKE_SOURCE_DIR}/src)
target_compile_options(fuzz_parsers PRIVATE ${FUZZ_FLAGS} -fsanitize=fuzzer-no-link)
target_link_libraries(fuzz_parsers PUBLIC PkgConfig::OIIO nlohmann_json::nlohmann_json)
set(SHADETWIN_FUZZ_SECONDS 20 CACHE STRING "seconds each fuzz target runs in ctest")
set(FUZZ_SEEDS ${CMAKE_BINARY_DIR}/fuzz_seeds)
enable_testing()
# Leaks inside libraries are suppressed by name (tests/lsan.supp, shared with the sanitizer build); every report in the
# project's code is fatal.
# (ASan's full unwinder on allocations: the fast one stops at libstdc++, before the library frames a suppression names.)
set(FUZZ_ENV "ASAN_OPTIONS=fast_unwind_on_malloc=0:malloc_context_size=30" "LSAN_OPTIONS=suppressions=${CMAKE_SOURCE_DIR}/tests/lsan.supp:print_suppressions=0" "UBSAN_OPTIONS=print_stacktrace=1")
add_test(NAME fuzz_seeds COMMAND bash ${CMAKE_SOURCE_DIR}/fuzz/make_seeds.sh ${CMAKE_SOURCE_DIR} ${FUZZ_SEEDS})
set_tests_properties(fuzz_seeds PROPERTIES FIXTURES_SETUP fuzz_seeds LABELS fuzz)
foreach(target scene mesh image device_desc)
  add_executable(fuzz_${target} fuzz/fuzz_${target}.cpp)
  target_link_libraries(fuzz_${target} PRIVATE fuzz_parsers)
  target_compile_definitions(fuzz_${target} PRIVATE SHADETWIN_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
  target_compile_options(fuzz_${target} PRIVATE ${FUZZ_FLAGS} -fsanitize=fuzzer)
  target_link_options(fuzz_${target} PRIVATE -fsanitize=address,undefined,fuzzer)
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz_${target}_corpus)
  # Bounded: SHADETWIN_FUZZ_SECONDS, one seed, 10 s per input, 4 GiB; new inputs into the build folder's corpus.
  add_test(NAME fuzz_${target}
           COMMAND fuzz_${target} -max_total_time=${SHADETWIN_FUZZ_SECONDS} -seed=1 -timeout=10 -rss_limit_mb=4096
                   -max_len=262144 -print_final_stats=1 -artifact_prefix=${CMAKE_BINARY_DIR}/fuzz_${target}_
                   ${CMAKE_BINARY_DIR}/fuzz_${target}_corpus ${FUZZ_SEEDS}/${target})
  set_tests_properties(fuzz_${target} PROPERTIES FIXTURES_REQUIRED fuzz_seeds LABELS fuzz ENVIRONMENT "${FUZZ_ENV}")
  # Every seed and every regression input once (a fuzz target given files runs each and exits).
  add_test(NAME fuzz_${target}_inputs COMMAND bash ${CMAKE_SOURCE_DIR}/fuzz/run_inputs.sh $<TARGET_FILE:fuzz_${target}>
           ${FUZZ_SEEDS}/${target} ${CMAKE_SOURCE_DIR}/fuzz/regressions/${target})
  set_tests_properties(fuzz_${target}_inputs PROPERTIES FIXTURES_REQUIRED fuzz_seeds LABELS fuzz ENVIRONMENT "${FUZZ_ENV}")
  # The seeds must load (a rejected seed aborts): the fuzzer starts from inputs that pass the parsers' checks.
  add_test(NAME fuzz_${target}_seeds_load COMMAND bash ${CMAKE_SOURCE_DIR}/fuzz/run_inputs.sh $<TARGET_FILE:fuzz_${target}>
           ${FUZZ_SEEDS}/${target})
  set_tests_properties(fuzz_${target}_seeds_load PROPERTIES FIXTURES_REQUIRED fuzz_seeds LABELS fuzz
                       ENVIRONMENT "${FUZZ_ENV};SHADETWIN_FUZZ_EXPECT_VALID=1")
endforeach()
