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
                     PROPERTIES LABELS sanitize ENVIRONMENT ${SAN_NO_LEAKS})  # exit status 0: every value bit-identical
