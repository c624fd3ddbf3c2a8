// The forward method's z-buffers as images (R32UI, one per eye): the winning key per eye pixel. The
// three-dispatch kernel reduces into them; the row kernel writes them from shared memory when asked
// (ForwardStereoPass::keys).
layout(binding = 4, r32ui) uniform coherent uimage2D leftKeys;
layout(binding = 5, r32ui) uniform coherent uimage2D rightKeys;
