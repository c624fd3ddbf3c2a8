/* The C API from C: a host device adopted, a device without s3d's features refused naming one, a bad format
 * refused, the stereo pass on uniform colour and depth (every visible eye pixel the colour, the cropped border
 * black), the HUD pass after it and inside it (a marker at its parallax in each eye), and the per-frame comfort
 * call with a C ray cast, with and without the disparity budget. Exit status 0 when every check holds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "capi_fixture.h"

static int failures = 0;
#define CHECK(condition, ...)                                  \
  do {                                                         \
    if (!(condition)) {                                        \
      fprintf(stderr, "test_capi.c:%d: ", __LINE__);           \
      fprintf(stderr, __VA_ARGS__);                            \
      fprintf(stderr, " (last error: %s)\n", s3d_last_error()); \
      ++failures;                                              \
    }                                                          \
  } while (0)
#define VK(call)                                                 \
  do {                                                           \
    VkResult r_ = (call);                                        \
    if (r_ != VK_SUCCESS) {                                      \
      fprintf(stderr, "test_capi.c:%d: %s = %d\n", __LINE__, #call, (int)r_); \
      return 1;                                                  \
    }                                                            \
  } while (0)

enum { W = 32, H = 8 };

static VkInstance instance;
static VkPhysicalDevice physical;
static VkDevice device;
static VkQueue queue;

static uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) {
  VkPhysicalDeviceMemoryProperties properties;
  vkGetPhysicalDeviceMemoryProperties(physical, &properties);
  for (uint32_t i = 0; i < properties.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (properties.memoryTypes[i].propertyFlags & flags) == flags) return i;
  return 0;
}

static int makeImage(VkFormat format, VkImageUsageFlags usage, VkImage* image, VkDeviceMemory* memory, VkImageView* view) {
  VkImageCreateInfo info = {VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent.width = W;
  info.extent.height = H;
  info.extent.depth = 1;
  info.mipLevels = info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.usage = usage;
  VK(vkCreateImage(device, &info, NULL, image));
  VkMemoryRequirements requirements;
  vkGetImageMemoryRequirements(device, *image, &requirements);
  VkMemoryAllocateInfo alloc = {VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex = memoryType(requirements.memoryTypeBits, 0);
  VK(vkAllocateMemory(device, &alloc, NULL, memory));
  VK(vkBindImageMemory(device, *image, *memory, 0));
  VkImageViewCreateInfo viewInfo = {VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = *image;
  viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = format;
  viewInfo.subresourceRange.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
  viewInfo.subresourceRange.levelCount = viewInfo.subresourceRange.layerCount = 1;
  VK(vkCreateImageView(device, &viewInfo, NULL, view));
  return 0;
}

static void barrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 srcStage,
                    VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
  b.subresourceRange.levelCount = b.subresourceRange.layerCount = 1;
  VkDependencyInfo dependency = {VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

static int32_t wallAtThree(void* user, const float origin[3], const float direction[3], float maxDistance, float* distance) {
  (void)user;
  (void)origin;
  (void)direction;
  if (maxDistance < 3.0f) return 0;
  *distance = 3.0f;
  return 1;
}

int main(void) {
  VkApplicationInfo app = {VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.apiVersion = s3d_required_api_version();
  VkInstanceCreateInfo instanceInfo = {VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  instanceInfo.pApplicationInfo = &app;
  VK(vkCreateInstance(&instanceInfo, NULL, &instance));
  uint32_t count = 8;
  VkPhysicalDevice devices[8];
  vkEnumeratePhysicalDevices(instance, &count, devices);
  for (uint32_t i = 0; i < count; ++i) {  /* the CPU device when there is one, as CI has */
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(devices[i], &properties);
    if (!physical || properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) physical = devices[i];
  }
  CHECK(s3d_required_extension_count() >= 1 && strcmp(s3d_required_extension(0), "VK_KHR_push_descriptor") == 0,
        "the push-descriptor extension is required");

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo = {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo deviceInfo = {VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;

  /* A device made without s3d's requirements is refused, naming a missing feature. */
  VkDevice plain;
  VK(vkCreateDevice(physical, &deviceInfo, NULL, &plain));
  s3d_host_device host = {instance, physical, plain, 0, VK_NULL_HANDLE, NULL, VK_NULL_HANDLE, &deviceInfo};
  vkGetDeviceQueue(plain, 0, 0, &host.queue);
  s3d_context refused = NULL;
  CHECK(s3d_context_create(&host, &refused) == S3D_ERROR_DEVICE_UNSUPPORTED, "a plain device is refused");
  CHECK(strstr(s3d_last_error(), "synchronization2") != NULL, "the error names synchronization2");
  vkDestroyDevice(plain, NULL);

  s3d_device_patch patch = NULL;
  CHECK(s3d_device_patch_apply(physical, &deviceInfo, &patch) == S3D_SUCCESS, "the patch applies");
  VK(vkCreateDevice(physical, &deviceInfo, NULL, &device));
  vkGetDeviceQueue(device, 0, 0, &queue);
  host.device = device;
  host.queue = queue;
  s3d_context context = NULL;
  CHECK(s3d_context_create(&host, &context) == S3D_SUCCESS, "the patched device is adopted");
  s3d_device_patch_destroy(patch);
  if (!context) return 1;

  s3d_host_pass_desc desc = {W, H, VK_FORMAT_R5G6B5_UNORM_PACK16, VK_FORMAT_R32_SFLOAT, S3D_OUTPUT_TWO_EYES, 0};
  s3d_host_pass pass = NULL;
  CHECK(s3d_host_pass_create(context, &desc, &pass) == S3D_ERROR_INVALID_ARGUMENT, "R5G6B5 is refused");
  CHECK(strstr(s3d_last_error(), "s3d_host_pass_desc.color_format") != NULL, "the error names the colour format");
  desc.color_format = VK_FORMAT_R8G8B8A8_UNORM;
  CHECK(s3d_host_pass_create(context, &desc, &pass) == S3D_SUCCESS, "an RGBA8 + R32F pass is made");
  if (!pass) return 1;

  /* Uniform colour and depth, cleared by the host; eyes read back through a buffer. */
  VkImage images[4];
  VkDeviceMemory memories[4];
  VkImageView views[4];
  const VkFormat formats[4] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_SFLOAT, s3d_host_pass_eye_format(pass),
                               s3d_host_pass_eye_format(pass)};
  for (int i = 0; i < 4; ++i)
    if (makeImage(formats[i], i < 2 ? VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT
                                    : VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                  &images[i], &memories[i], &views[i]))
      return 1;
  VkBufferCreateInfo bufferInfo = {VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bufferInfo.size = 2 * W * H * 4;
  bufferInfo.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkBuffer buffer;
  VK(vkCreateBuffer(device, &bufferInfo, NULL, &buffer));
  VkMemoryRequirements requirements;
  vkGetBufferMemoryRequirements(device, buffer, &requirements);
  VkMemoryAllocateInfo alloc = {VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex = memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory bufferMemory;
  VK(vkAllocateMemory(device, &alloc, NULL, &bufferMemory));
  VK(vkBindBufferMemory(device, buffer, bufferMemory, 0));

  VkCommandPoolCreateInfo poolInfo = {VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  VkCommandPool pool;
  VK(vkCreateCommandPool(device, &poolInfo, NULL, &pool));
  VkCommandBufferAllocateInfo cmdInfo = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cmdInfo.commandPool = pool;
  cmdInfo.commandBufferCount = 1;
  VkCommandBuffer cmd;
  VK(vkAllocateCommandBuffers(device, &cmdInfo, &cmd));
  VkCommandBufferBeginInfo begin = {VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  VK(vkBeginCommandBuffer(cmd, &begin));
  const VkImageSubresourceRange range = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  const VkClearColorValue orange = {.float32 = {1.0f, 0.5f, 0.0f, 1.0f}}, depthFive = {.float32 = {5.0f, 0, 0, 0}};
  for (int i = 0; i < 2; ++i)
    barrier(cmd, images[i], VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
            VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  vkCmdClearColorImage(cmd, images[0], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &orange, 1, &range);
  vkCmdClearColorImage(cmd, images[1], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &depthFive, 1, &range);
  for (int i = 2; i < 4; ++i)
    barrier(cmd, images[i], VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
            VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  /* s3d adds the barriers from the clears and back: the host states each image's last access. */
  const s3d_host_image color = {images[0], views[0], formats[0], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
  const s3d_host_image depth = {images[1], views[1], formats[1], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
  const s3d_host_image left = {images[2], views[2], formats[2], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
  s3d_host_image right = left;
  right.image = images[3];
  right.view = views[3];
  s3d_stereo_parameters parameters;
  s3d_default_stereo_parameters(&parameters);
  parameters.max_separation = 0.1f; /* 3.2 px: a 4-column black border each side */
  CHECK(s3d_host_pass_record(pass, cmd, &color, &depth, &parameters, NULL, &left, &right, NULL) == S3D_SUCCESS,
        "the pass records");
  VkBufferImageCopy copy = {0};
  copy.imageSubresource.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
  copy.imageSubresource.layerCount = 1;
  copy.imageExtent.width = W;
  copy.imageExtent.height = H;
  copy.imageExtent.depth = 1;
  vkCmdCopyImageToBuffer(cmd, images[2], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &copy);
  copy.bufferOffset = W * H * 4;
  vkCmdCopyImageToBuffer(cmd, images[3], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &copy);
  VK(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit = {VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  VK(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE));
  VK(vkQueueWaitIdle(queue));
  unsigned char* texels;
  VK(vkMapMemory(device, bufferMemory, 0, VK_WHOLE_SIZE, 0, (void**)&texels));
  int wrong = 0;
  for (int eye = 0; eye < 2; ++eye)
    for (int x = 0; x < W; ++x) {
      const unsigned char* p = texels + eye * W * H * 4 + (H / 2 * W + x) * 4;
      const int border = x < 4 || x >= W - 4;
      const unsigned char expected[4] = {border ? 0 : 255, border ? 0 : 128, 0, 255};
      for (int c = 0; c < 4; ++c) wrong += abs((int)p[c] - (int)expected[c]) > 1;
    }
  CHECK(wrong == 0, "%d channels differ from the uniform colour or the black border", wrong);

  /* The HUD: a 2x2 white marker s3d uploads, anchored at (16, 4) with 1 px parallax (left eye 15-16, right 17-18),
   * first recorded after the stereo pass, then inside it (s3d_host_pass_record_with_hud) at -2 px. */
  unsigned char white[2 * 2 * 4];
  memset(white, 255, sizeof white);
  const s3d_hud_element_desc marker = {"marker", {16.0f, 4.0f, 0, 0}, white, 2, 2};
  const s3d_hud_pass_desc hudDesc = {W, H, 0, &marker, 1};
  s3d_hud_pass hudPass = NULL;
  CHECK(s3d_hud_pass_create(context, &hudDesc, &hudPass) == S3D_SUCCESS, "the HUD pass is made");
  if (!hudPass) return 1;
  CHECK(s3d_hud_pass_element_count(hudPass) == 1, "one element");
  for (int round = 0; round < 2; ++round) {
    const s3d_hud_element_frame hudFrame = {round == 0 ? 1.0f : -2.0f, 0, 0};
    VK(vkResetCommandPool(device, pool, 0));
    VK(vkBeginCommandBuffer(cmd, &begin));
    if (round == 0) {
      CHECK(s3d_host_pass_record(pass, cmd, &color, &depth, &parameters, NULL, &left, &right, NULL) == S3D_SUCCESS,
            "the pass records");
      CHECK(s3d_hud_pass_record(hudPass, cmd, &hudFrame, 1, NULL, 0, &left, &right) == S3D_SUCCESS, "the HUD records");
      CHECK(s3d_hud_pass_record(hudPass, cmd, &hudFrame, 0, NULL, 0, &left, &right) == S3D_ERROR_INVALID_ARGUMENT &&
                strstr(s3d_last_error(), "frame_count 0") != NULL,
            "a missing element state is refused");
    } else {
      CHECK(s3d_host_pass_record_with_hud(pass, cmd, &color, &depth, &parameters, NULL, &left, &right, NULL, hudPass,
                                          &hudFrame, 1, NULL, 0) == S3D_SUCCESS,
            "the pass records with the HUD");
    }
    copy.bufferOffset = 0;
    vkCmdCopyImageToBuffer(cmd, images[2], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &copy);
    copy.bufferOffset = W * H * 4;
    vkCmdCopyImageToBuffer(cmd, images[3], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &copy);
    VK(vkEndCommandBuffer(cmd));
    VK(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE));
    VK(vkQueueWaitIdle(queue));
    wrong = 0;
    for (int eye = 0; eye < 2; ++eye) {
      const int first = 16 + (eye == 0 ? -1 : 1) * (int)hudFrame.parallax_px; /* rounded half up: exact here */
      for (int y = 3; y < 7; ++y)
        for (int x = 4; x < W - 4; ++x) {
          const unsigned char* p = texels + eye * W * H * 4 + (y * W + x) * 4;
          const int marked = x >= first && x < first + 2 && y >= 4 && y < 6;
          const unsigned char expected[4] = {255, marked ? 255 : 128, marked ? 255 : 0, 255};
          for (int c = 0; c < 4; ++c) wrong += abs((int)p[c] - (int)expected[c]) > 1;
        }
    }
    CHECK(wrong == 0, "round %d: %d channels differ from the orange eyes with the white marker", round, wrong);
  }
  /* Every refusal a careless caller is owed, recorded into a command buffer that is then dropped. */
  VK(vkResetCommandPool(device, pool, 0));
  VK(vkBeginCommandBuffer(cmd, &begin));
  const capi_fixture fixture = {physical, host, &deviceInfo, context, pass, hudPass, cmd, color, depth, left, right};
  failures += capi_argument_checks(&fixture);
  VK(vkEndCommandBuffer(cmd));
  VK(vkResetCommandPool(device, pool, 0));
  s3d_hud_pass_destroy(hudPass);

  /* Per-frame comfort through a C ray cast. */
  s3d_frame_comfort_input input;
  memset(&input, 0, sizeof input);
  input.camera_aim[2] = -1.0f;
  input.camera_near = 0.1f;
  input.ray_cast = wallAtThree;
  s3d_default_stereo_parameters(&input.parameters);
  input.parameters.zero_parallax_distance = 4.0f;
  input.width = 1000;
  input.crosshair_distance = 10.0f;
  input.crosshair_margin = 0.5f;
  const float hudDepths[2] = {1.0f, 8.0f};
  input.hud_depths = hudDepths;
  input.hud_count = 2;
  s3d_frame_comfort_state state;
  s3d_hud_element_state hud[2];
  CHECK(s3d_frame_comfort_state_compute(&input, &state, hud) == S3D_SUCCESS, "the comfort state is computed");
  CHECK(state.crosshair_hit_world && fabsf(state.crosshair.depth - 4.0f) < 1e-6f,
        "the crosshair (2.5 m before the wall) is held at the screen plane, got %f", state.crosshair.depth);
  CHECK(hud[0].depth == 4.0f && hud[1].depth == 8.0f && hud[1].parallax_px > 0.0f, "HUD depths and parallax");

  /* The disparity budget: a 27-inch monitor at 0.7 m, a frame from 3 m to the sky. The first frame jumps to the
   * target: the plane at the nearest depth, the sky at 90 % of the uncrossed budget between the eyes. */
  const s3d_display monitor = {0.5977f, 0.7f, 0.063f, 0.0f};
  s3d_budget_controller controller = NULL;
  CHECK(s3d_budget_controller_create(&monitor, 0, &controller) == S3D_SUCCESS, "the budget controller is created");
  s3d_frame_budget budget;
  memset(&budget, 0, sizeof budget);
  budget.controller = controller;
  budget.depth.nearest = 3.0f;
  budget.depth.farthest = 50.0f;
  budget.depth.sky_pixels = 100;
  budget.frame_seconds = 1.0f / 60.0f;
  s3d_budget_choice choice;
  CHECK(s3d_frame_comfort_state_compute_budgeted(&input, &budget, &state, hud, &choice) == S3D_SUCCESS,
        "the budgeted comfort state is computed");
  CHECK(choice.chosen && choice.cut && state.parameters.zero_parallax_distance == 3.0f &&
            state.parameters.max_separation == choice.max_separation,
        "the controller's choice is the frame's parameters (plane %f)", state.parameters.zero_parallax_distance);
  CHECK(fabsf(2.0f * choice.max_separation - 0.9f * choice.uncrossed_fraction) < 1e-5f &&
            choice.uncrossed_fraction > 0.015f && choice.uncrossed_fraction < 0.03f,
        "the sky fills 90 %% of the uncrossed budget (%f of %f)", 2.0f * choice.max_separation,
        choice.uncrossed_fraction);
  CHECK(hud[0].depth == 3.0f, "the HUD follows the chosen plane, got %f", hud[0].depth);
  budget.depth.nearest = NAN;
  CHECK(s3d_frame_comfort_state_compute_budgeted(&input, &budget, &state, hud, &choice) == S3D_ERROR_INVALID_ARGUMENT,
        "a NaN depth range is refused");
  s3d_budget_controller_destroy(controller);
  const s3d_display badEyes = {0.6f, 0.7f, 0.2f, 0.0f};
  CHECK(s3d_budget_controller_create(&badEyes, 0, &controller) == S3D_ERROR_INVALID_ARGUMENT &&
            strstr(s3d_last_error(), "s3d_display.interocular_meters") != NULL,
        "a 20 cm interocular distance is refused naming the field");
  const s3d_display headset = {0.0f, 1.3f, 0.063f, 90.0f};
  CHECK(s3d_budget_controller_create(&headset, 1, &controller) == S3D_SUCCESS, "a head-mounted display's budget");
  s3d_budget_controller_destroy(controller);

  input.width = 0;
  CHECK(s3d_frame_comfort_state_compute(&input, &state, hud) == S3D_ERROR_INVALID_ARGUMENT, "width 0 is refused");

  s3d_host_pass_destroy(pass);
  s3d_context_destroy(context);
  vkDestroyCommandPool(device, pool, NULL);
  vkDestroyBuffer(device, buffer, NULL);
  vkFreeMemory(device, bufferMemory, NULL);
  for (int i = 0; i < 4; ++i) {
    vkDestroyImageView(device, views[i], NULL);
    vkDestroyImage(device, images[i], NULL);
    vkFreeMemory(device, memories[i], NULL);
  }
  vkDestroyDevice(device, NULL);
  vkDestroyInstance(instance, NULL);
  if (failures == 0) printf("test_capi: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
