/* A plain-C host on the installed package only: its own Vulkan instance and device (s3d's requirements added by
 * s3d_device_patch_apply), its own colour (a horizontal ramp) and linear depth (top half near, bottom half at the
 * zero-parallax distance), s3d's stereo frame (the forward method) recorded into its own command buffer with one
 * dispatch description that gives the eyes' views as OpenXR reports them, the eyes read back.
 * Checks: at the zero-parallax distance both eyes show the input; nearer, the eyes are shifted apart by the
 * parallax. Exit status 0 when every check holds.
 *   cmake --install build --prefix /tmp/s3d
 *   cc host.c $(PKG_CONFIG_PATH=/tmp/s3d/lib/pkgconfig pkg-config --cflags --libs s3d) -o host_c && ./host_c
 * or with CMake: CMakeLists.txt here. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <s3d/s3d.h>

enum { W = 64, H = 8, PIXELS = W * H };
#define ZERO_PARALLAX 4.0f
#define NEAR_DEPTH 2.0f
#define MAX_SEPARATION 0.05f /* of the width: 3.2 px at infinity */
#define HALF_BASELINE 0.0325f /* metres: eyes 65 mm apart */

#define VK(call)                                                                                  \
  do {                                                                                           \
    VkResult r_ = (call);                                                                        \
    if (r_ != VK_SUCCESS) {                                                                      \
      fprintf(stderr, "host.c:%d: %s failed (VkResult %d)\n", __LINE__, #call, (int)r_);          \
      exit(1);                                                                                   \
    }                                                                                            \
  } while (0)
#define S3D(call)                                                                                  \
  do {                                                                                            \
    if ((call) != S3D_SUCCESS) {                                                                  \
      fprintf(stderr, "host.c:%d: s3d refused: %s\n", __LINE__, s3d_last_error());                 \
      exit(1);                                                                                    \
    }                                                                                             \
  } while (0)

static VkPhysicalDevice physical;
static VkDevice device;
static VkDeviceMemory memories[4]; /* the images' */
static int memoryCount;

static uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) {
  VkPhysicalDeviceMemoryProperties properties;
  vkGetPhysicalDeviceMemoryProperties(physical, &properties);
  for (uint32_t i = 0; i < properties.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (properties.memoryTypes[i].propertyFlags & flags) == flags) return i;
  fprintf(stderr, "host.c: no memory type with flags 0x%x\n", (unsigned)flags);
  exit(1);
}

/* A W x H image and its view; the last access is stated to s3d, which adds the barriers around its pass. */
static s3d_host_image makeImage(VkFormat format, VkImageUsageFlags usage, VkImageLayout layout,
                                VkPipelineStageFlags2 stage, VkAccessFlags2 access) {
  VkImageCreateInfo info = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO, .imageType = VK_IMAGE_TYPE_2D,
                            .format = format, .extent = {W, H, 1}, .mipLevels = 1, .arrayLayers = 1,
                            .samples = VK_SAMPLE_COUNT_1_BIT, .usage = usage};
  s3d_host_image image = {.format = format, .layout = layout, .stage = stage, .access = access};
  VK(vkCreateImage(device, &info, NULL, &image.image));
  VkMemoryRequirements requirements;
  vkGetImageMemoryRequirements(device, image.image, &requirements);
  VkMemoryAllocateInfo alloc = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = requirements.size,
                                .memoryTypeIndex = memoryType(requirements.memoryTypeBits, 0)};
  VkDeviceMemory* memory = &memories[memoryCount++];
  VK(vkAllocateMemory(device, &alloc, NULL, memory));
  VK(vkBindImageMemory(device, image.image, *memory, 0));
  VkImageViewCreateInfo view = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, .image = image.image,
                                .viewType = VK_IMAGE_VIEW_TYPE_2D, .format = format,
                                .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
  VK(vkCreateImageView(device, &view, NULL, &image.view));
  return image;
}

static void toLayout(VkCommandBuffer cmd, VkImage image, VkImageLayout layout, VkPipelineStageFlags2 stage,
                     VkAccessFlags2 access) {
  VkImageMemoryBarrier2 barrier = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2, .dstStageMask = stage,
                                   .dstAccessMask = access, .oldLayout = VK_IMAGE_LAYOUT_UNDEFINED, .newLayout = layout,
                                   .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                   .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED, .image = image,
                                   .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}};
  VkDependencyInfo dependency = {.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = 1,
                                 .pImageMemoryBarriers = &barrier};
  vkCmdPipelineBarrier2(cmd, &dependency);
}

/* The CPU device (lavapipe) when there is one, and its first queue family with compute. */
static uint32_t pickDevice(VkInstance instance) {
  VkPhysicalDevice devices[8];
  uint32_t count = 8;
  if (vkEnumeratePhysicalDevices(instance, &count, devices) < 0) count = 0;
  for (uint32_t i = 0; i < count; ++i) {
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(devices[i], &properties);
    if (!physical || properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) physical = devices[i];
  }
  if (!physical) {
    fprintf(stderr, "host.c: no Vulkan device (install mesa-vulkan-drivers for lavapipe)\n");
    exit(1);
  }
  VkQueueFamilyProperties families[16];
  uint32_t familyCount = 16, family = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &familyCount, families);
  while (family < familyCount && !(families[family].queueFlags & VK_QUEUE_COMPUTE_BIT)) ++family;
  if (family == familyCount) {
    fprintf(stderr, "host.c: the Vulkan device has no compute queue, which s3d's passes need\n");
    exit(1);
  }
  return family;
}

/* The host's device, with s3d's extensions and features added; then s3d adopts it. */
static s3d_context createDeviceAndContext(VkInstance instance, uint32_t family, VkQueue* queue) {
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, .queueFamilyIndex = family,
                                       .queueCount = 1, .pQueuePriorities = &priority};
  VkDeviceCreateInfo deviceInfo = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .queueCreateInfoCount = 1,
                                   .pQueueCreateInfos = &queueInfo};
  s3d_device_patch patch;
  S3D(s3d_device_patch_apply(physical, &deviceInfo, &patch));
  VK(vkCreateDevice(physical, &deviceInfo, NULL, &device));
  vkGetDeviceQueue(device, family, 0, queue);
  const s3d_host_device host = {instance, physical, device, family, *queue, NULL, VK_NULL_HANDLE, &deviceInfo};
  s3d_context context;
  S3D(s3d_context_create(&host, &context));
  s3d_device_patch_destroy(patch);
  return context;
}

/* One host-visible buffer: [colour | depth] uploaded, [left | right] read back, 4 bytes a texel each. The colour is
 * a horizontal ramp; the depth is NEAR_DEPTH in the top half, the zero-parallax distance in the bottom half. */
static unsigned char* makeStagingBuffer(VkBuffer* buffer, VkDeviceMemory* memory) {
  VkBufferCreateInfo bufferInfo = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = 4 * PIXELS * 4,
                                   .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT};
  VK(vkCreateBuffer(device, &bufferInfo, NULL, buffer));
  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(device, *buffer, &requirements);
  VkMemoryAllocateInfo alloc = {
      .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, .allocationSize = requirements.size,
      .memoryTypeIndex = memoryType(requirements.memoryTypeBits,
                                    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)};
  VK(vkAllocateMemory(device, &alloc, NULL, memory));
  VK(vkBindBufferMemory(device, *buffer, *memory, 0));
  unsigned char* mapped;
  VK(vkMapMemory(device, *memory, 0, VK_WHOLE_SIZE, 0, (void**)&mapped));
  float* linearDepth = (float*)(mapped + PIXELS * 4);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      unsigned char* p = mapped + (y * W + x) * 4;
      p[0] = (unsigned char)(x * 4), p[1] = (unsigned char)(255 - x * 4), p[2] = 128, p[3] = 255;
      linearDepth[y * W + x] = y < H / 2 ? NEAR_DEPTH : ZERO_PARALLAX;
    }
  return mapped;
}

/* The eyes' views (XrView: offset in metres, fov angles in radians) of a screen's converging pair, from which s3d
 * derives the separation and the zero-parallax distance: each frustum shifted towards the other eye by
 * HALF_BASELINE / ZERO_PARALLAX in tangent units, MAX_SEPARATION of its width. */
static s3d_eye_views screenEyeViews(void) {
  const float toward = HALF_BASELINE / ZERO_PARALLAX, half = toward / MAX_SEPARATION / 2.0f, up = atanf(half * H / W);
  const s3d_eye_views views = {{-HALF_BASELINE, atanf(-half + toward), atanf(half + toward), up, -up},
                               {HALF_BASELINE, atanf(-half - toward), atanf(half - toward), up, -up}, 1.0f};
  return views;
}

/* Crossed parallax at NEAR_DEPTH: max_separation * (ZERO_PARALLAX / NEAR_DEPTH - 1) * W = 3.2 px, the left eye
 * showing the input from 3.2 px to the left, the right eye from 3.2 px to the right; the red ramp rises 4 a pixel,
 * so about 13 less and 13 more. At the zero-parallax distance both eyes are the input. Columns away from the cropped
 * borders (3.2 px a side) and the shift. Returns the number of wrong pixels. */
static int checkEyes(const unsigned char* mapped) {
  const unsigned char* rgba = mapped;
  const float* linearDepth = (const float*)(mapped + PIXELS * 4);
  const float shift = MAX_SEPARATION * (ZERO_PARALLAX / NEAR_DEPTH - 1.0f) * W;
  const int redShift = (int)(4.0f * shift + 0.5f);
  const unsigned char* eyes[2] = {mapped + 2 * PIXELS * 4, mapped + 3 * PIXELS * 4};
  int failures = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 8; x < W - 8; ++x) {
      const int i = (y * W + x) * 4, l = eyes[0][i], r = eyes[1][i], want = y < H / 2 ? redShift : 0;
      if (abs(l - (rgba[i] - want)) > 1 || abs(r - (rgba[i] + want)) > 1) {
        if (failures++ < 8)
          fprintf(stderr, "host_c: pixel (%d, %d), depth %.1f: red left %d right %d, expected %d and %d\n", x, y,
                  linearDepth[y * W + x], l, r, rgba[i] - want, rgba[i] + want);
      }
    }
  return failures;
}

/* One command buffer of the host's: the inputs uploaded, s3d's stereo frame recorded with one dispatch description,
 * the eyes read back; submitted and waited for. images: colour, depth, left, right. */
static void runFrame(uint32_t family, VkQueue queue, s3d_stereo_frame frame, const s3d_host_image images[4],
                     VkBuffer buffer) {
  const VkImageLayout dst = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, src = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  const VkPipelineStageFlags2 copy = VK_PIPELINE_STAGE_2_COPY_BIT;
  VkCommandPoolCreateInfo poolInfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, .queueFamilyIndex = family};
  VkCommandPool pool;
  VK(vkCreateCommandPool(device, &poolInfo, NULL, &pool));
  VkCommandBufferAllocateInfo cmdInfo = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, .commandPool = pool,
                                         .commandBufferCount = 1};
  VkCommandBuffer cmd;
  VK(vkAllocateCommandBuffers(device, &cmdInfo, &cmd));
  VkCommandBufferBeginInfo begin = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  VK(vkBeginCommandBuffer(cmd, &begin));
  for (int i = 0; i < 4; ++i)
    toLayout(cmd, images[i].image, i < 2 ? dst : src, copy, i < 2 ? VK_ACCESS_2_TRANSFER_WRITE_BIT : VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, .imageExtent = {W, H, 1}};
  for (int i = 0; i < 2; ++i, region.bufferOffset += PIXELS * 4)
    vkCmdCopyBufferToImage(cmd, buffer, images[i].image, dst, 1, &region);

  s3d_stereo_frame_dispatch dispatch;
  s3d_default_stereo_frame_dispatch(&dispatch);
  dispatch.color = images[0], dispatch.depth = images[1], dispatch.left = images[2], dispatch.right = images[3];
  const s3d_eye_views views = screenEyeViews();
  dispatch.eye_views = &views; /* instead of max_separation and zero_parallax_distance */
  S3D(s3d_stereo_frame_record(frame, cmd, &dispatch));
  for (int i = 2; i < 4; ++i, region.bufferOffset += PIXELS * 4)
    vkCmdCopyImageToBuffer(cmd, images[i].image, src, buffer, 1, &region);
  VK(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO, .commandBufferCount = 1, .pCommandBuffers = &cmd};
  VK(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE));
  VK(vkQueueWaitIdle(queue));
  vkDestroyCommandPool(device, pool, NULL);
}

int main(void) {
  VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .pApplicationName = "s3d C host",
                           .apiVersion = s3d_required_api_version()};
  VkInstanceCreateInfo instanceInfo = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &app};
  VkInstance instance;
  VK(vkCreateInstance(&instanceInfo, NULL, &instance));
  const uint32_t family = pickDevice(instance);
  VkQueue queue;
  s3d_context context = createDeviceAndContext(instance, family, &queue);

  s3d_stereo_frame_desc desc;
  s3d_default_stereo_frame_desc(&desc);
  desc.width = W, desc.height = H;
  desc.color_format = VK_FORMAT_R8G8B8A8_UNORM, desc.depth_format = VK_FORMAT_R32_SFLOAT;
  desc.method = S3D_METHOD_FORWARD;
  s3d_stereo_frame frame;
  S3D(s3d_stereo_frame_create(context, &desc, &frame));

  /* Inputs written by a copy, eyes read by a copy: s3d is told each image's layout and last access. */
  const VkImageUsageFlags in = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  const VkImageUsageFlags out = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  const VkImageLayout dst = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, src = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  const VkPipelineStageFlags2 copy = VK_PIPELINE_STAGE_2_COPY_BIT;
  const s3d_host_image color = makeImage(desc.color_format, in, dst, copy, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  const s3d_host_image depth = makeImage(desc.depth_format, in, dst, copy, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  const VkFormat eyeFormat = s3d_stereo_frame_eye_format(frame);
  if (eyeFormat != VK_FORMAT_R8G8B8A8_UNORM) { /* the checks below read the eyes as bytes */
    fprintf(stderr, "host.c: expected RGBA8 eyes for RGBA8 colour, s3d chose format %d\n", (int)eyeFormat);
    return 1;
  }
  const s3d_host_image left = makeImage(eyeFormat, out, src, copy, VK_ACCESS_2_TRANSFER_READ_BIT);
  const s3d_host_image right = makeImage(eyeFormat, out, src, copy, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBuffer buffer;
  VkDeviceMemory bufferMemory;
  const unsigned char* mapped = makeStagingBuffer(&buffer, &bufferMemory);

  runFrame(family, queue, frame, (const s3d_host_image[4]){color, depth, left, right}, buffer);
  const int failures = checkEyes(mapped);

  s3d_stereo_frame_destroy(frame);
  s3d_context_destroy(context); /* s3d destroys none of the host's handles: the host's own go below */
  vkDestroyBuffer(device, buffer, NULL);
  vkFreeMemory(device, bufferMemory, NULL);
  const s3d_host_image* all[4] = {&color, &depth, &left, &right};
  for (int i = 0; i < 4; ++i) {
    vkDestroyImageView(device, all[i]->view, NULL);
    vkDestroyImage(device, all[i]->image, NULL);
    vkFreeMemory(device, memories[i], NULL);
  }
  vkDestroyDevice(device, NULL);
  vkDestroyInstance(instance, NULL);
  if (failures) {
    fprintf(stderr, "host_c: %d pixels wrong\n", failures);
    return 1;
  }
  printf("host_c: near rows shifted apart between the eyes, zero-parallax rows equal to the input\n");
  return 0;
}
