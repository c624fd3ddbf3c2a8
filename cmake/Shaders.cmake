# s3d_add_shaders(TARGET target SOURCES a.comp b.frag ... [INCLUDE_DIRS dir ...])
# Compiles GLSL to SPIR-V at build time (a GLSL error fails the build) and embeds each module into
# the target as a constexpr uint32_t array in a generated header <s3d_spirv/NAME_STAGE.h>, so the
# binaries need no shader files at run time.
function(s3d_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET" "SOURCES;INCLUDE_DIRS" ${ARGN})
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/s3d_spirv")
  file(MAKE_DIRECTORY "${out_dir}/s3d_spirv")
  set(include_flags "")
  set(depends "")
  foreach(dir ${ARG_INCLUDE_DIRS})
    list(APPEND include_flags "-I${dir}")
    file(GLOB_RECURSE headers "${dir}/*.h" "${dir}/*.glsl")
    list(APPEND depends ${headers})
  endforeach()
  set(outputs "")
  foreach(src ${ARG_SOURCES})
    get_filename_component(abs "${src}" ABSOLUTE)
    get_filename_component(name "${src}" NAME)
    string(REPLACE "." "_" symbol "${name}")
    set(header "${out_dir}/s3d_spirv/${symbol}.h")
    add_custom_command(
      OUTPUT "${header}"
      COMMAND Vulkan::glslangValidator --target-env vulkan1.3 ${include_flags}
              --vn "spirv_${symbol}" -o "${header}" "${abs}"
      DEPENDS "${abs}" ${depends}
      COMMENT "GLSL -> SPIR-V ${name}"
      VERBATIM)
    list(APPEND outputs "${header}")
  endforeach()
  target_sources(${ARG_TARGET} PRIVATE ${outputs})
  target_include_directories(${ARG_TARGET} PRIVATE "${out_dir}")
endfunction()
