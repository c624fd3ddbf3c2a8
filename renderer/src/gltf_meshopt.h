#pragma once
// EXT_meshopt_compression: buffer views whose data lies compressed in another buffer, decoded with Debian's
// meshoptimizer before any accessor reads them.
#include <filesystem>

#include <tiny_gltf.h>

#include "gltf_reader.h"

namespace s3d::renderer::gltf {

// Decodes every buffer view with the extension into a buffer of its own (appended to the model) and points the
// view at it. The decoded bytes count against `memory` before they are allocated; a stream that does not decode,
// or a view whose fields break the extension's rules, is refused naming the file and the buffer view.
void decodeMeshoptViews(const std::filesystem::path& file, tinygltf::Model& model, SceneMemory& memory);

}  // namespace s3d::renderer::gltf
