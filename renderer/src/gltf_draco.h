#pragma once
// KHR_draco_mesh_compression: primitives whose attributes and faces lie in one draco stream, decoded with Debian's
// libdraco before the scene is built.
#include <filesystem>

#include <tiny_gltf.h>

#include "gltf_reader.h"

namespace s3d::renderer::gltf {

// Decodes every primitive with the extension into float accessors (the attributes its `attributes` map names)
// and 32-bit indices of a buffer of its own (appended to the model), and points the primitive at them. The
// decoded data counts against `memory` (sized from the accessors the file declares, before decoding); a stream
// that does not decode or does not match its accessors is refused naming the file, the mesh and the primitive.
void decodeDracoPrimitives(const std::filesystem::path& file, tinygltf::Model& model, SceneMemory& memory);

}  // namespace s3d::renderer::gltf
