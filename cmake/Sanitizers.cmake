# S3D_SANITIZE: instrument every target with the listed sanitizers (e.g. address,undefined).
# Any report aborts the program (no recovery), so a test that trips one fails; see .ci/run's build-asan job.
set(S3D_SANITIZE "" CACHE STRING "Comma-separated -fsanitize= list for every target, e.g. address,undefined")
if(S3D_SANITIZE)
  add_compile_options(-fsanitize=${S3D_SANITIZE} -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${S3D_SANITIZE})
endif()

# S3D_BUILD_FUZZERS: libFuzzer targets for the file loaders (tests/fuzz), clang only. Every target is
# built with coverage instrumentation (fuzzer-no-link) so the fuzzers see the loaders' branches.
option(S3D_BUILD_FUZZERS "Build the libFuzzer targets in tests/fuzz (needs clang with libFuzzer)" OFF)
if(S3D_BUILD_FUZZERS)
  include(CheckCXXSourceCompiles)
  set(CMAKE_REQUIRED_FLAGS "-fsanitize=fuzzer")
  check_cxx_source_compiles([[
    #include <cstddef>
    #include <cstdint>
    extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }]] S3D_HAVE_LIBFUZZER)
  unset(CMAKE_REQUIRED_FLAGS)
  if(NOT S3D_HAVE_LIBFUZZER)
    message(FATAL_ERROR "S3D_BUILD_FUZZERS needs a compiler with libFuzzer: configure with "
                        "-DCMAKE_CXX_COMPILER=clang++ (Debian packages clang, libclang-rt-14-dev)")
  endif()
  # The C targets (the C API test) get the same instrumentation, so the C compiler must be clang too.
  if(NOT CMAKE_C_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "S3D_BUILD_FUZZERS needs clang as the C compiler as well: configure with "
                        "-DCMAKE_C_COMPILER=clang (found ${CMAKE_C_COMPILER_ID})")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

# s3d_sanitizer_options(target): an S3D_SANITIZE executable gets cmake/sanitizer_options.cpp (its defaults).
# Called from s3d_set_warnings, which every project target calls; libraries are skipped.
function(s3d_sanitizer_options target)
  get_target_property(type ${target} TYPE)
  if(S3D_SANITIZE AND type STREQUAL "EXECUTABLE")
    target_sources(${target} PRIVATE "${PROJECT_SOURCE_DIR}/cmake/sanitizer_options.cpp")
  endif()
endfunction()
