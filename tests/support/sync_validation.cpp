// Linked into the test binaries that run under the Khronos validation layer with synchronization validation
// (tests/CMakeLists.txt, VALIDATED): set before any Vulkan instance is made, unless the environment already names
// layers; the fixtures then fail a case on any message.
#include <cstdlib>

namespace {

const bool kSyncValidation = [] {
  setenv("VK_INSTANCE_LAYERS", "VK_LAYER_KHRONOS_validation", 0);
  setenv("VK_LAYER_ENABLES", "VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT", 0);
  return true;
}();

}  // namespace
