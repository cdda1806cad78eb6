# The sanitizer build's tests beyond the unit suite (issue 20), included from CMakeLists.txt when SHADETWIN_SANITIZE is on
# (the release build's differential suites and benchmarks are not registered there).
#
# A differential subset: each stage's verify suite once on lavapipe, small sizes (the emulator and the Vulkan host code
# under the sanitizers; the sizes keep the run within CI's budget), labelled sanitize.
add_test(NAME san_verify_math COMMAND shadetwin verify math --count 2000 --seed 1)
add_test(NAME san_verify_texture COMMAND shadetwin verify texture --count 256 --seed 1 --seeds 2)
add_test(NAME san_verify_mips COMMAND shadetwin verify mips --count 3 --seed 1)
add_test(NAME san_verify_frame_bunny COMMAND shadetwin verify frame --scene ${CMAKE_SOURCE_DIR}/scenes/bunny.json
         --width 48 --height 48 --validate)
add_test(NAME san_verify_frame_env_mis COMMAND shadetwin verify frame --scene ${CMAKE_SOURCE_DIR}/scenes/ward_spheres.json
         --width 48 --height 24 --validate)
set_tests_properties(san_verify_math san_verify_texture san_verify_mips san_verify_frame_bunny san_verify_frame_env_mis
                     PROPERTIES LABELS sanitize)  # the exit status: 0 only when every value is bit-identical

# libFuzzer targets (fuzz/*.cpp; clang only): the parsers of every input file the project reads. Each runs for a bounded
# time from its seed corpus (fuzz/make_seeds.sh: the shipped scenes, device descriptions, npm meshes, a glTF triangle
# and its binary twin, small EXR/HDR/PNG); what it finds goes to fuzz_<target>_corpus/ in the build folder and a crash
# to fuzz_<target>_crash-*, which becomes a regression input under fuzz/regressions/<target>/ (run by the
# fuzz_<target>_regressions test).
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  set(SHADETWIN_FUZZ_SECONDS 30 CACHE STRING "seconds each fuzz target runs in ctest")
  set(FUZZ_SEEDS ${CMAKE_BINARY_DIR}/fuzz_seeds)
  add_test(NAME fuzz_seeds COMMAND bash ${CMAKE_SOURCE_DIR}/fuzz/make_seeds.sh ${CMAKE_SOURCE_DIR} ${FUZZ_SEEDS})
  set_tests_properties(fuzz_seeds PROPERTIES FIXTURES_SETUP fuzz_seeds LABELS fuzz)
  # Coverage for the fuzzer in the code it targets only (the rest of the unit suite runs without the counters).
  set_property(SOURCE src/scene/scene.cpp src/scene/mesh.cpp src/scene/tinygltf_impl.cpp src/util/image_io.cpp
               src/model/device_desc.cpp TARGET_DIRECTORY shadetwin_core APPEND PROPERTY COMPILE_OPTIONS -fsanitize=fuzzer-no-link)
  foreach(target scene mesh image device_desc)
    add_executable(fuzz_${target} fuzz/fuzz_${target}.cpp)
    target_link_libraries(fuzz_${target} PRIVATE shadetwin_core)
    target_compile_definitions(fuzz_${target} PRIVATE SHADETWIN_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
    target_compile_options(fuzz_${target} PRIVATE -fsanitize=fuzzer)
    target_link_options(fuzz_${target} PRIVATE -fsanitize=fuzzer)
    file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz_${target}_corpus)
    add_test(NAME fuzz_${target}
             COMMAND fuzz_${target} -max_total_time=${SHADETWIN_FUZZ_SECONDS} -seed=1 -timeout=10 -rss_limit_mb=4096
                     -max_len=262144 -artifact_prefix=${CMAKE_BINARY_DIR}/fuzz_${target}_
                     ${CMAKE_BINARY_DIR}/fuzz_${target}_corpus ${FUZZ_SEEDS}/${target})
    set_tests_properties(fuzz_${target} PROPERTIES FIXTURES_REQUIRED fuzz_seeds LABELS fuzz)
    # Every seed and every regression input once (a fuzz target given files runs each and exits).
    file(GLOB regressions ${CMAKE_SOURCE_DIR}/fuzz/regressions/${target}/*)
    add_test(NAME fuzz_${target}_seeds COMMAND sh -c "'$<TARGET_FILE:fuzz_${target}>' '${FUZZ_SEEDS}/${target}'/* ${regressions}")
    set_tests_properties(fuzz_${target}_seeds PROPERTIES FIXTURES_REQUIRED fuzz_seeds LABELS fuzz)
  endforeach()
endif()
