# s3d_set_warnings(target): the project's warning level on one target.
function(s3d_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
    # Vulkan structs are initialised as {sType}, the rest zero: that idiom is intended.
    -Wno-missing-field-initializers)
  if(S3D_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  s3d_sanitizer_options(${target})
endfunction()
