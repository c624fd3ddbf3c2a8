// Default sanitizer options compiled into every executable of an S3D_SANITIZE build (cmake/Sanitizers.cmake),
// so `ctest --test-dir build-asan` and the s3d tool behave the same with or without environment variables;
// ASAN_OPTIONS / UBSAN_OPTIONS / LSAN_OPTIONS set by hand still override these.
extern "C" {

// Any report ends the process with a stack trace, so a test that trips one fails.
const char* __asan_default_options() { return "strict_string_checks=1:check_initialization_order=1"; }
const char* __ubsan_default_options() { return "halt_on_error=1:print_stacktrace=1"; }

}  // extern "C"

// LeakSanitizer checks at exit, after the Vulkan loader has dlclose'd the driver and the layer: their
// leaks would show as "<unknown module>" and no suppression could name them. Keeping every library
// mapped (as Vulkan-Loader's newer VK_LOADER_DISABLE_DYNAMIC_LIBRARY_UNLOADING=1 does) keeps them named.
extern "C" int dlclose(void*) { return 0; }

// Quiet about the suppressions used: the CLI tests check that an error is exactly one stderr line.
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }

extern "C" const char* __lsan_default_suppressions() {
  // Blocks allocated inside Mesa lavapipe itself (first frame in libvulkan_lvp.so) that it never frees:
  // seen since the shadow/glTF renderer passes (RenderJob, CoverSequence, regress tests). s3d's own Vulkan
  // objects are the validation layer's job; whether these come from an s3d object left alive at
  // vkDestroyDevice is still to be checked (docs/DESIGN.md "Robustness").
  // Blocks the Khronos validation layer allocates for its synchronization validation state and never frees
  // (only indirect leaks, all first framed in the layer; seen in the host tests, which turn synchronization
  // validation on for their own device): any object s3d left alive would be the layer's own report at
  // vkDestroyDevice, which those tests fail on.
  return "leak:libvulkan_lvp.so\nleak:libVkLayer_khronos_validation.so\n";
}
