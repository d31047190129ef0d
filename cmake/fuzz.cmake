# fuzz.cmake - libFuzzer targets (tests/fuzz/README.md), built instead of the
# program when FLOWFORM_FUZZ is ON. Needs clang (Debian's clang and
# libclang-rt-14-dev):
#   cmake -S . -B build-fuzz -DFLOWFORM_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang
# The readers under test (src/core, src/target, src/scene and the viewer's
# script reader) are compiled with AddressSanitizer, UndefinedBehaviorSanitizer
# and libFuzzer's coverage; they use OpenMP only through pragmas, which a
# serial build ignores.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "FLOWFORM_FUZZ needs clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
endif()
set(FF_FUZZ_FLAGS -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                  -fno-omit-frame-pointer -g -O1)
file(GLOB FF_FUZZ_LIB_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/core/*.cpp ${CMAKE_SOURCE_DIR}/src/target/*.cpp
     ${CMAKE_SOURCE_DIR}/src/scene/*.cpp)
add_library(flowform_fuzz_readers STATIC ${FF_FUZZ_LIB_SOURCES} ${CMAKE_SOURCE_DIR}/src/viewer/script.cpp
                                         ${CMAKE_BINARY_DIR}/generated/resources.cpp)
target_include_directories(flowform_fuzz_readers PUBLIC ${CMAKE_SOURCE_DIR}/src ${CMAKE_SOURCE_DIR}/kernels/common
                           ${CMAKE_SOURCE_DIR})
target_link_libraries(flowform_fuzz_readers PUBLIC Eigen3::Eigen nlohmann_json::nlohmann_json PkgConfig::ASSIMP)
target_compile_options(flowform_fuzz_readers PUBLIC ${FF_FUZZ_FLAGS} -Wno-unknown-pragmas)
target_link_options(flowform_fuzz_readers PUBLIC -fsanitize=address,undefined)

function(ff_fuzz_target name source)
  add_executable(${name} ${CMAKE_SOURCE_DIR}/tests/fuzz/${source})
  target_link_libraries(${name} PRIVATE flowform_fuzz_readers)
  target_link_options(${name} PRIVATE -fsanitize=fuzzer)
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR})
endfunction()

ff_fuzz_target(fuzz_scene fuzz_scene.cpp)
ff_fuzz_target(fuzz_script fuzz_script.cpp)
foreach(fmt obj ply stl off)
  ff_fuzz_target(fuzz_mesh_${fmt} fuzz_mesh.cpp)
  target_compile_definitions(fuzz_mesh_${fmt} PRIVATE FF_FUZZ_EXT=".${fmt}")
endforeach()
