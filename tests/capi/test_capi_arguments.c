/* The C API against careless calls: every function refuses a NULL handle or pointer, an out-of-range enum, a
 * non-finite or out-of-range float and a size past the device's maxImageDimension2D with
 * S3D_ERROR_INVALID_ARGUMENT, and its message names the C parameter or field, never a C++ function. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "capi_fixture.h"

static int failures = 0;

/* Words of the C++ library's own messages that must not reach a C caller. */
static const char* const internalNames[] = {"::", "HostStereoPass", "HudPass", "HostProjection", "frameComfortState",
                                            "placeCrosshair", "maxSeparation", "zeroParallaxDistance",
                                            "interocularMeters", "display profile", "disparity budget control",
                                            "DeviceRequirementsPatch", "deviceRequirements"};

static void expectRefused(int line, s3d_result result, const char* name) {
  const char* message = s3d_last_error();
  int ok = result == S3D_ERROR_INVALID_ARGUMENT && strstr(message, name) != NULL;
  for (size_t i = 0; i < sizeof internalNames / sizeof *internalNames; ++i) ok = ok && !strstr(message, internalNames[i]);
  if (!ok) {
    fprintf(stderr, "test_capi_arguments.c:%d: expected S3D_ERROR_INVALID_ARGUMENT naming '%s' in the C API's words, "
                    "got %d: %s\n", line, name, (int)result, message);
    ++failures;
  }
}
#define REFUSED(call, name) expectRefused(__LINE__, (call), (name))
#define EXPECT(condition, what)                                                                   \
  do {                                                                                            \
    if (!(condition)) {                                                                           \
      fprintf(stderr, "test_capi_arguments.c:%d: %s (last error: %s)\n", __LINE__, what, s3d_last_error()); \
      ++failures;                                                                                 \
    }                                                                                             \
  } while (0)

/* One float field set to one bad value; the field's C name is expected in the message. */
typedef struct float_case {
  size_t offset;
  float value;
  const char* name;
} float_case;
#define FIELD(type, member, value) {offsetof(type, member), (value), #member}

static void setFloat(void* object, const float_case* c) { memcpy((char*)object + c->offset, &c->value, sizeof c->value); }

static s3d_frame_comfort_input validInput(void) {
  s3d_frame_comfort_input input;
  memset(&input, 0, sizeof input);
  input.camera_aim[2] = -1.0f;
  input.camera_near = 0.1f;
  s3d_default_stereo_parameters(&input.parameters);
  input.width = 640;
  input.crosshair_distance = 10.0f;
  input.crosshair_margin = 0.25f;
  input.weapon_pixels = 100;
  input.weapon_nearest_depth = 0.3f;
  input.weapon_farthest_depth = 0.6f;
  input.has_nearest_world_depth = 1;
  input.nearest_world_depth = 5.0f;
  return input;
}

/* s3d_device_patch_apply with a null physical device crashed inside the driver. */
static void nullPhysicalDeviceIsRefused(const capi_fixture* f) {
  s3d_device_patch patch = NULL;
  REFUSED(s3d_device_patch_apply(VK_NULL_HANDLE, f->device_info, &patch), "physical_device");
  EXPECT(patch == NULL, "no patch is made");
}

/* Sizes near 2^32 crashed inside the driver; sizes past the limit passed to the validation layer. */
static void sizesPastTheDeviceLimitAreRefused(const capi_fixture* f) {
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(f->physical, &properties);
  const uint32_t limit = properties.limits.maxImageDimension2D;
  s3d_host_pass pass = NULL;
  s3d_host_pass_desc desc = {0xFFFFFFF0u, 8, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_SFLOAT, S3D_OUTPUT_TWO_EYES, 0};
  REFUSED(s3d_host_pass_create(f->context, &desc, &pass), "s3d_host_pass_desc.width 4294967280 exceeds");
  EXPECT(strstr(s3d_last_error(), "maxImageDimension2D") != NULL, "the message names the device limit");
  desc.width = 8;
  desc.height = 0xFFFFFFFFu;
  REFUSED(s3d_host_pass_create(f->context, &desc, &pass), "s3d_host_pass_desc.height");
  desc.height = limit + 1;
  REFUSED(s3d_host_pass_create(f->context, &desc, &pass), "s3d_host_pass_desc.height");
  /* The packed target doubles the width (height) of full side-by-side (top-bottom). */
  desc.height = 1;
  desc.width = limit / 2 + 1;
  desc.output = S3D_OUTPUT_SIDE_BY_SIDE_FULL;
  REFUSED(s3d_host_pass_create(f->context, &desc, &pass), "S3D_OUTPUT_SIDE_BY_SIDE_FULL");
  desc.width = 1;
  desc.height = limit / 2 + 1;
  desc.output = S3D_OUTPUT_TOP_BOTTOM_FULL;
  REFUSED(s3d_host_pass_create(f->context, &desc, &pass), "S3D_OUTPUT_TOP_BOTTOM_FULL");
  EXPECT(pass == NULL, "no pass is made");
  desc.width = limit / 2;
  desc.height = 1;
  desc.output = S3D_OUTPUT_SIDE_BY_SIDE_FULL;
  EXPECT(s3d_host_pass_create(f->context, &desc, &pass) == S3D_SUCCESS, "a packed target of exactly the limit is made");
  s3d_host_pass_destroy(pass);
  s3d_hud_pass hud = NULL;
  s3d_hud_pass_desc hudDesc = {limit + 1, 8, 1, NULL, 0};
  REFUSED(s3d_hud_pass_create(f->context, &hudDesc, &hud), "s3d_hud_pass_desc.width");
  const s3d_hud_element_desc wide = {"wide", {0.0f, 0.0f, 0, 0}, NULL, limit + 1, 1};
  const s3d_hud_pass_desc wideElement = {8, 8, 0, &wide, 1};
  REFUSED(s3d_hud_pass_create(f->context, &wideElement, &hud), "s3d_hud_pass_desc.elements[0].width");
}

/* A negative, zero or non-finite nearest depth gave a negative zero-parallax distance and S3D_SUCCESS. */
static void nonPositiveNearestWorldDepthIsRefused(void) {
  const float bad[] = {-2.0f, 0.0f, NAN, INFINITY};
  s3d_frame_comfort_state state;
  for (size_t i = 0; i < sizeof bad / sizeof *bad; ++i) {
    s3d_frame_comfort_input input = validInput();
    input.nearest_world_depth = bad[i];
    REFUSED(s3d_frame_comfort_state_compute(&input, &state, NULL), "s3d_frame_comfort_input.nearest_world_depth");
  }
}

/* The C++ functions' messages (placeCrosshair:, frameComfortState:, HostStereoPass:) are C API messages now. */
static void messagesNameTheCField(const capi_fixture* f) {
  s3d_frame_comfort_state state;
  s3d_frame_comfort_input input = validInput();
  input.crosshair_distance = 0.0f;
  REFUSED(s3d_frame_comfort_state_compute(&input, &state, NULL), "s3d_frame_comfort_input.crosshair_distance");
  input = validInput();
  input.width = 0;
  REFUSED(s3d_frame_comfort_state_compute(&input, &state, NULL), "s3d_frame_comfort_input.width");
  s3d_stereo_parameters parameters;
  s3d_default_stereo_parameters(&parameters);
  s3d_host_image color = f->color;
  color.image = VK_NULL_HANDLE;
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &color, &f->depth, &parameters, NULL, &f->left, &f->right, NULL),
          "color.image");
}

static void nullHandlesAndPointers(const capi_fixture* f) {
  s3d_device_patch patch = NULL;
  REFUSED(s3d_device_patch_apply(f->physical, NULL, &patch), "info is NULL");
  REFUSED(s3d_device_patch_apply(f->physical, f->device_info, NULL), "out is NULL");
  s3d_context context = NULL;
  REFUSED(s3d_context_create(NULL, &context), "host is NULL");
  REFUSED(s3d_context_create(&f->host, NULL), "out is NULL");
  const char* const hostFields[] = {"s3d_host_device.instance", "s3d_host_device.physical_device",
                                    "s3d_host_device.device", "s3d_host_device.queue", "s3d_host_device.queue_family"};
  for (int i = 0; i < 5; ++i) {
    s3d_host_device host = f->host;
    if (i == 0) host.instance = VK_NULL_HANDLE;
    if (i == 1) host.physical_device = VK_NULL_HANDLE;
    if (i == 2) host.device = VK_NULL_HANDLE;
    if (i == 3) host.queue = VK_NULL_HANDLE;
    if (i == 4) host.queue_family = 1000;
    REFUSED(s3d_context_create(&host, &context), hostFields[i]);
  }
  const s3d_host_pass_desc desc = {8, 8, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_SFLOAT, S3D_OUTPUT_TWO_EYES, 0};
  s3d_host_pass pass = NULL;
  REFUSED(s3d_host_pass_create(NULL, &desc, &pass), "context is NULL");
  REFUSED(s3d_host_pass_create(f->context, NULL, &pass), "desc is NULL");
  REFUSED(s3d_host_pass_create(f->context, &desc, NULL), "out is NULL");
  const s3d_hud_pass_desc hudDesc = {8, 8, 1, NULL, 0};
  s3d_hud_pass hud = NULL;
  REFUSED(s3d_hud_pass_create(NULL, &hudDesc, &hud), "context is NULL");
  REFUSED(s3d_hud_pass_create(f->context, NULL, &hud), "desc is NULL");
  REFUSED(s3d_hud_pass_create(f->context, &hudDesc, NULL), "out is NULL");
  s3d_budget_controller controller = NULL;
  const s3d_display monitor = {0.6f, 0.7f, 0.063f, 0.0f};
  REFUSED(s3d_budget_controller_create(NULL, 0, &controller), "display is NULL");
  REFUSED(s3d_budget_controller_create(&monitor, 0, NULL), "out is NULL");
  s3d_frame_comfort_input input = validInput();
  s3d_frame_comfort_state state;
  REFUSED(s3d_frame_comfort_state_compute(NULL, &state, NULL), "input is NULL");
  REFUSED(s3d_frame_comfort_state_compute(&input, NULL, NULL), "out is NULL");
  input.hud_count = 1;
  REFUSED(s3d_frame_comfort_state_compute(&input, &state, NULL), "s3d_frame_comfort_input.hud_depths");
  EXPECT(s3d_host_pass_eye_format(NULL) == VK_FORMAT_UNDEFINED && strstr(s3d_last_error(), "pass"),
         "a NULL pass has no eye format, and the last error says so");
  EXPECT(s3d_hud_pass_element_count(NULL) == 0 && strstr(s3d_last_error(), "pass"), "a NULL HUD pass has no elements");
  EXPECT(s3d_required_extension(1000) == NULL && strstr(s3d_last_error(), "index"), "no extension past the count");
}

static void hostPassDescriptions(const capi_fixture* f) {
  const s3d_host_pass_desc valid = {8, 8, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32_SFLOAT, S3D_OUTPUT_TWO_EYES, 0};
  struct { s3d_host_pass_desc desc; const char* name; } cases[] = {
      {valid, "s3d_host_pass_desc.output"}, {valid, "s3d_host_pass_desc.output"},
      {valid, "s3d_host_pass_desc.width is 0"}, {valid, "s3d_host_pass_desc.height is 0"},
      {valid, "s3d_host_pass_desc.color_format"}, {valid, "s3d_host_pass_desc.depth_format"},
      {valid, "s3d_host_pass_desc.inputs_are_storage"}, {valid, "S3D_OUTPUT_SIDE_BY_SIDE_HALF"},
      {valid, "S3D_OUTPUT_TOP_BOTTOM_HALF"}};
  cases[0].desc.output = (s3d_output)6;
  cases[1].desc.output = (s3d_output)-1;
  cases[2].desc.width = 0;
  cases[3].desc.height = 0;
  cases[4].desc.color_format = VK_FORMAT_R5G6B5_UNORM_PACK16;
  cases[5].desc.depth_format = VK_FORMAT_R8_UNORM;
  cases[6].desc.inputs_are_storage = 1;
  cases[6].desc.color_format = VK_FORMAT_B8G8R8A8_UNORM;
  cases[7].desc.output = S3D_OUTPUT_SIDE_BY_SIDE_HALF;
  cases[7].desc.width = 1;
  cases[8].desc.output = S3D_OUTPUT_TOP_BOTTOM_HALF;
  cases[8].desc.height = 1;
  for (size_t i = 0; i < sizeof cases / sizeof *cases; ++i) {
    s3d_host_pass pass = NULL;
    REFUSED(s3d_host_pass_create(f->context, &cases[i].desc, &pass), cases[i].name);
  }
}

static void hudPassDescriptions(const capi_fixture* f) {
  const s3d_hud_element_desc element = {"e", {1.0f, 1.0f, 0, 0}, NULL, 2, 2};
  s3d_hud_element_desc elements[17];
  for (int i = 0; i < 17; ++i) elements[i] = element;
  elements[1].placement.anchor_y = NAN;
  elements[2].height = 0;
  const struct { s3d_hud_pass_desc desc; const char* name; } cases[] = {
      {{0, 8, 0, elements, 1}, "s3d_hud_pass_desc.width is 0"},
      {{8, 0, 0, elements, 1}, "s3d_hud_pass_desc.height is 0"},
      {{8, 8, 0, elements, 17}, "s3d_hud_pass_desc.element_count 17"},
      {{8, 8, 1, elements, 14}, "s3d_hud_pass_desc.element_count 14"},  /* with the 3 built-in ones */
      {{8, 8, 0, NULL, 1}, "s3d_hud_pass_desc.elements is NULL"},
      {{8, 8, 0, elements, 2}, "s3d_hud_pass_desc.elements[1].placement.anchor_y"},
      {{8, 8, 0, elements + 2, 1}, "s3d_hud_pass_desc.elements[0].height is 0"}};
  for (size_t i = 0; i < sizeof cases / sizeof *cases; ++i) {
    s3d_hud_pass hud = NULL;
    REFUSED(s3d_hud_pass_create(f->context, &cases[i].desc, &hud), cases[i].name);
  }
  const s3d_hud_pass_desc tiny = {1, 1, 1, NULL, 0};
  s3d_hud_pass hud = NULL;
  EXPECT(s3d_hud_pass_create(f->context, &tiny, &hud) == S3D_SUCCESS, "the built-in HUD on a 1x1 eye is made");
  s3d_hud_pass_destroy(hud);
}

static void stereoParametersAndProjection(const capi_fixture* f) {
  s3d_stereo_parameters valid;
  s3d_default_stereo_parameters(&valid);
  const float_case floats[] = {
      FIELD(s3d_stereo_parameters, max_separation, NAN), FIELD(s3d_stereo_parameters, max_separation, 0.3f),
      FIELD(s3d_stereo_parameters, max_separation, -0.1f), FIELD(s3d_stereo_parameters, zero_parallax_distance, 0.0f),
      FIELD(s3d_stereo_parameters, zero_parallax_distance, INFINITY), FIELD(s3d_stereo_parameters, edge_crop, NAN),
      FIELD(s3d_stereo_parameters, edge_crop, 0.5f), FIELD(s3d_stereo_parameters, weapon_depth_offset, -1.0f),
      FIELD(s3d_stereo_parameters, weapon_depth_scale, 0.0f), FIELD(s3d_stereo_parameters, weapon_depth_scale, NAN)};
  char name[64];
  for (size_t i = 0; i < sizeof floats / sizeof *floats; ++i) {
    s3d_stereo_parameters p = valid;
    setFloat(&p, &floats[i]);
    snprintf(name, sizeof name, "parameters.%s", floats[i].name);
    REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, &f->depth, &p, NULL, &f->left, &f->right, NULL), name);
  }
  s3d_stereo_parameters p = valid;
  p.method = (s3d_method)2;
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, &f->depth, &p, NULL, &f->left, &f->right, NULL),
          "parameters.method");
  p.method = S3D_METHOD_SEARCH;
  p.search_taps = 17;
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, &f->depth, &p, NULL, &f->left, &f->right, NULL),
          "parameters.search_taps");

  const s3d_projection projection = {0.1f, 100.0f, 0, 0, 0.5f, 0.01f, 1.0f};
  const float_case planes[] = {
      FIELD(s3d_projection, near_plane, 0.0f), FIELD(s3d_projection, near_plane, NAN),
      FIELD(s3d_projection, far_plane, 0.05f), FIELD(s3d_projection, far_plane, INFINITY),
      FIELD(s3d_projection, first_person_depth_range, 1.0f), FIELD(s3d_projection, first_person_depth_range, -0.1f),
      FIELD(s3d_projection, first_person_depth_range, NAN), FIELD(s3d_projection, first_person_near, 0.0f),
      FIELD(s3d_projection, first_person_far, 0.001f)};
  for (size_t i = 0; i < sizeof planes / sizeof *planes; ++i) {
    s3d_projection bad = projection;
    setFloat(&bad, &planes[i]);
    snprintf(name, sizeof name, "projection.%s", planes[i].name);
    REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, &f->depth, &valid, &bad, &f->left, &f->right, NULL), name);
  }
}

static void recordImages(const capi_fixture* f) {
  s3d_stereo_parameters p;
  s3d_default_stereo_parameters(&p);
  REFUSED(s3d_host_pass_record(NULL, f->cmd, &f->color, &f->depth, &p, NULL, &f->left, &f->right, NULL), "pass is NULL");
  REFUSED(s3d_host_pass_record(f->pass, NULL, &f->color, &f->depth, &p, NULL, &f->left, &f->right, NULL), "cmd is VK_NULL_HANDLE");
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, NULL, &f->depth, &p, NULL, &f->left, &f->right, NULL), "color is NULL");
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, NULL, &p, NULL, &f->left, &f->right, NULL), "depth is NULL");
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, &f->depth, NULL, NULL, &f->left, &f->right, NULL),
          "parameters is NULL");
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, &f->depth, &p, NULL, NULL, &f->right, NULL), "left is NULL");
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, &f->depth, &p, NULL, &f->left, NULL, NULL), "right is NULL");
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, &f->depth, &p, NULL, &f->left, &f->right, &f->left),
          "target must be NULL");
  s3d_host_image color = f->color, depth = f->depth, left = f->left;
  color.view = VK_NULL_HANDLE;
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &color, &f->depth, &p, NULL, &f->left, &f->right, NULL), "color.view");
  depth.format = VK_FORMAT_D32_SFLOAT;
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, &depth, &p, NULL, &f->left, &f->right, NULL),
          "depth.format");
  color = f->color;
  color.stage = 0; /* the host synchronizes it, in a layout s3d cannot sample */
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &color, &f->depth, &p, NULL, &f->left, &f->right, NULL),
          "color.layout");
  left.stage = 0;
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, &f->depth, &p, NULL, &left, &f->right, NULL), "left.layout");
  left = f->left;
  left.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  REFUSED(s3d_host_pass_record(f->pass, f->cmd, &f->color, &f->depth, &p, NULL, &left, &f->right, NULL), "left.format");

  const s3d_hud_element_frame frame = {1.0f, 0, 0}, nanFrame = {NAN, 0, 0};
  REFUSED(s3d_hud_pass_record(NULL, f->cmd, &frame, 1, NULL, 0, &f->left, &f->right), "pass is NULL");
  REFUSED(s3d_hud_pass_record(f->hud, NULL, &frame, 1, NULL, 0, &f->left, &f->right), "cmd is VK_NULL_HANDLE");
  REFUSED(s3d_hud_pass_record(f->hud, f->cmd, NULL, 1, NULL, 0, &f->left, &f->right), "frames is NULL");
  REFUSED(s3d_hud_pass_record(f->hud, f->cmd, &frame, 2, NULL, 0, &f->left, &f->right), "frame_count 2");
  REFUSED(s3d_hud_pass_record(f->hud, f->cmd, &nanFrame, 1, NULL, 0, &f->left, &f->right), "frames[0].parallax_px");
  REFUSED(s3d_hud_pass_record(f->hud, f->cmd, &frame, 1, &f->color, 1, &f->left, &f->right), "host_layer_count 1");
  REFUSED(s3d_hud_pass_record(f->hud, f->cmd, &frame, 1, NULL, 0, NULL, &f->right), "left is NULL");
  REFUSED(s3d_host_pass_record_with_hud(f->pass, f->cmd, &f->color, &f->depth, &p, NULL, &f->left, &f->right, NULL,
                                       NULL, &frame, 1, NULL, 0),
          "hud is NULL");
  REFUSED(s3d_host_pass_record_with_hud(NULL, f->cmd, &f->color, &f->depth, &p, NULL, &f->left, &f->right, NULL,
                                       f->hud, &frame, 1, NULL, 0),
          "pass is NULL");
}

static int32_t nanRayCast(void* user, const float origin[3], const float direction[3], float maxDistance,
                          float* distance) {
  (void)user;
  (void)origin;
  (void)direction;
  (void)maxDistance;
  *distance = NAN;
  return 1;
}

static void comfortInputs(void) {
  const float_case floats[] = {
      FIELD(s3d_frame_comfort_input, camera_position[0], NAN),
      FIELD(s3d_frame_comfort_input, camera_aim[1], INFINITY),
      FIELD(s3d_frame_comfort_input, camera_aim[2], -2.0f),
      FIELD(s3d_frame_comfort_input, camera_near, 0.0f),
      FIELD(s3d_frame_comfort_input, camera_near, NAN),
      FIELD(s3d_frame_comfort_input, parameters.max_separation, NAN),
      FIELD(s3d_frame_comfort_input, parameters.zero_parallax_distance, -1.0f),
      FIELD(s3d_frame_comfort_input, parameters.weapon_depth_scale, INFINITY),
      FIELD(s3d_frame_comfort_input, crosshair_distance, INFINITY),
      FIELD(s3d_frame_comfort_input, crosshair_margin, -1.0f),
      FIELD(s3d_frame_comfort_input, crosshair_margin, NAN),
      FIELD(s3d_frame_comfort_input, weapon_nearest_depth, 0.0f),
      FIELD(s3d_frame_comfort_input, weapon_farthest_depth, NAN),
      FIELD(s3d_frame_comfort_input, weapon_farthest_depth, 0.1f)};
  s3d_frame_comfort_state state;
  char name[80];
  for (size_t i = 0; i < sizeof floats / sizeof *floats; ++i) {
    s3d_frame_comfort_input input = validInput();
    setFloat(&input, &floats[i]);
    snprintf(name, sizeof name, "s3d_frame_comfort_input.%.*s", (int)strcspn(floats[i].name, "["), floats[i].name);
    REFUSED(s3d_frame_comfort_state_compute(&input, &state, NULL), name);
  }
  s3d_frame_comfort_input input = validInput();
  input.parameters.method = (s3d_method)-1;
  REFUSED(s3d_frame_comfort_state_compute(&input, &state, NULL), "s3d_frame_comfort_input.parameters.method");
  const float depths[2] = {1.0f, -1.0f};
  s3d_hud_element_state hud[2];
  input = validInput();
  input.hud_depths = depths;
  input.hud_count = 2;
  REFUSED(s3d_frame_comfort_state_compute(&input, &state, hud), "s3d_frame_comfort_input.hud_depths[1]");
  input.hud_depths = depths + 0;
  input.hud_count = 1;
  REFUSED(s3d_frame_comfort_state_compute(&input, &state, NULL), "hud_states is NULL");
  input = validInput();
  input.ray_cast = nanRayCast;
  REFUSED(s3d_frame_comfort_state_compute(&input, &state, NULL), "s3d_frame_comfort_input.ray_cast");
  EXPECT(s3d_frame_comfort_state_compute_budgeted(&input, NULL, &state, NULL, NULL) == S3D_ERROR_INVALID_ARGUMENT,
         "the budgeted call checks the input too");
}

static void displaysAndBudgets(void) {
  const s3d_display monitor = {0.6f, 0.7f, 0.063f, 0.0f}, headset = {0.0f, 1.3f, 0.063f, 90.0f};
  const float_case floats[] = {
      FIELD(s3d_display, viewing_distance_meters, 0.0f), FIELD(s3d_display, viewing_distance_meters, 101.0f),
      FIELD(s3d_display, viewing_distance_meters, NAN), FIELD(s3d_display, interocular_meters, 0.2f),
      FIELD(s3d_display, interocular_meters, NAN), FIELD(s3d_display, screen_width_meters, 0.0f),
      FIELD(s3d_display, screen_width_meters, INFINITY), FIELD(s3d_display, field_of_view_degrees, -1.0f),
      FIELD(s3d_display, field_of_view_degrees, NAN)};
  s3d_budget_controller controller = NULL;
  char name[64];
  for (size_t i = 0; i < sizeof floats / sizeof *floats; ++i) {
    s3d_display display = monitor;
    setFloat(&display, &floats[i]);
    snprintf(name, sizeof name, "s3d_display.%s", floats[i].name);
    REFUSED(s3d_budget_controller_create(&display, 0, &controller), name);
  }
  s3d_display wide = headset;
  wide.field_of_view_degrees = 170.0f;
  REFUSED(s3d_budget_controller_create(&wide, 0, &controller), "s3d_display.field_of_view_degrees");
  wide.field_of_view_degrees = 160.0f;
  wide.viewing_distance_meters = 50.0f; /* a virtual screen 567 m wide */
  REFUSED(s3d_budget_controller_create(&wide, 0, &controller), "s3d_display.viewing_distance_meters");

  EXPECT(s3d_budget_controller_create(&monitor, 0, &controller) == S3D_SUCCESS, "a monitor's budget");
  s3d_frame_budget valid;
  memset(&valid, 0, sizeof valid);
  valid.controller = controller;
  valid.depth.nearest = 2.0f;
  valid.depth.farthest = 40.0f;
  valid.frame_seconds = 1.0f / 60.0f;
  const float_case budgetFloats[] = {
      FIELD(s3d_frame_budget, frame_seconds, 0.0f), FIELD(s3d_frame_budget, frame_seconds, NAN),
      FIELD(s3d_frame_budget, depth.nearest, NAN), FIELD(s3d_frame_budget, depth.nearest, -1.0f),
      FIELD(s3d_frame_budget, depth.farthest, INFINITY)};
  const s3d_frame_comfort_input input = validInput();
  s3d_frame_comfort_state state;
  for (size_t i = 0; i < sizeof budgetFloats / sizeof *budgetFloats; ++i) {
    s3d_frame_budget budget = valid;
    setFloat(&budget, &budgetFloats[i]);
    REFUSED(s3d_frame_comfort_state_compute_budgeted(&input, &budget, &state, NULL, NULL), "s3d_frame_budget.");
  }
  s3d_frame_budget budget = valid;
  budget.has_anticipated_nearest = 1;
  budget.anticipated_nearest = -1.0f;
  REFUSED(s3d_frame_comfort_state_compute_budgeted(&input, &budget, &state, NULL, NULL),
          "s3d_frame_budget.anticipated_nearest");
  budget = valid;
  budget.depth.histogram_bins = 4;
  REFUSED(s3d_frame_comfort_state_compute_budgeted(&input, &budget, &state, NULL, NULL),
          "s3d_frame_budget.depth.histogram");
  budget = valid;
  budget.controller = NULL;
  REFUSED(s3d_frame_comfort_state_compute_budgeted(&input, &budget, &state, NULL, NULL), "s3d_frame_budget.controller");
  s3d_frame_comfort_input negative = input;
  negative.allow_negative_parallax = 1;
  REFUSED(s3d_frame_comfort_state_compute_budgeted(&negative, &valid, &state, NULL, NULL), "allow_negative_parallax");
  s3d_budget_controller_destroy(controller);
}

/* A screen's off-axis pair: tangents +-0.5 shifted by 0.01625 towards the other eye (converging at 2 m). */
static s3d_eye_views tvPair(void) {
  const float up = atanf(0.28125f);
  const s3d_eye_views views = {{-0.0325f, atanf(-0.48375f), atanf(0.51625f), up, -up},
                               {0.0325f, atanf(-0.51625f), atanf(0.48375f), up, -up}, 1.0f};
  return views;
}

static void eyeViews(const capi_fixture* f) {
  s3d_eye_views_stereo derived;
  s3d_eye_views views = tvPair();
  EXPECT(s3d_stereo_for_eye_views(&views, 1920, 1080, &derived) == S3D_SUCCESS, "the TV pair is taken");
  EXPECT(fabsf(derived.zero_parallax_distance - 2.0f) < 1e-3f && fabsf(derived.max_separation - 0.01625f) < 1e-5f &&
             fabsf(derived.center.angle_left + atanf(0.5f)) < 1e-5f && derived.center.position_x == 0.0f,
         "the TV pair converges at 2 m, its center camera between the eyes with the screen's frustum");
  REFUSED(s3d_stereo_for_eye_views(NULL, 1920, 1080, &derived), "views is NULL");
  REFUSED(s3d_stereo_for_eye_views(&views, 1920, 1080, NULL), "out is NULL");
  REFUSED(s3d_stereo_for_eye_views(&views, 0, 1080, &derived), "width is 0");
  const s3d_eye_views headset = {{-0.0315f, -0.7854f, 0.6981f, 0.7330f, -0.8203f},
                                 {0.0315f, -0.6981f, 0.7854f, 0.7330f, -0.8203f}, 1.0f};
  REFUSED(s3d_stereo_for_eye_views(&headset, 1920, 1080, &derived), "views->left.angle_left");
  views.world_scale = NAN;
  REFUSED(s3d_stereo_for_eye_views(&views, 1920, 1080, &derived), "views->world_scale");
  views = tvPair();
  views.left.angle_down = 2.0f;
  REFUSED(s3d_stereo_for_eye_views(&views, 1920, 1080, &derived), "views->left.angle_down");
  views = tvPair();
  views.right.position_x = -0.05f;
  REFUSED(s3d_stereo_for_eye_views(&views, 1920, 1080, &derived), "views->right.position_x");
  /* In a dispatch: an RGBA8 + R32F stereo frame of the fixture's size, its images; refused before recording. */
  s3d_stereo_frame_desc desc;
  s3d_default_stereo_frame_desc(&desc);
  desc.width = 32, desc.height = 8;
  desc.color_format = f->color.format, desc.depth_format = f->depth.format;
  s3d_stereo_frame frame = NULL;
  EXPECT(s3d_stereo_frame_create(f->context, &desc, &frame) == S3D_SUCCESS, "a stereo frame is made");
  s3d_stereo_frame_dispatch dispatch;
  s3d_default_stereo_frame_dispatch(&dispatch);
  dispatch.color = f->color, dispatch.depth = f->depth, dispatch.left = f->left, dispatch.right = f->right;
  views = tvPair();
  views.right.angle_up = atanf(0.5f); /* another vertical field than the left eye's */
  dispatch.eye_views = &views;
  REFUSED(s3d_stereo_frame_record(frame, f->cmd, &dispatch), "dispatch.eye_views->right.angle_up");
  s3d_stereo_frame_destroy(frame);
}

int capi_argument_checks(const capi_fixture* fixture) {
  nullPhysicalDeviceIsRefused(fixture);
  sizesPastTheDeviceLimitAreRefused(fixture);
  nonPositiveNearestWorldDepthIsRefused();
  messagesNameTheCField(fixture);
  nullHandlesAndPointers(fixture);
  hostPassDescriptions(fixture);
  hudPassDescriptions(fixture);
  stereoParametersAndProjection(fixture);
  recordImages(fixture);
  comfortInputs();
  displaysAndBudgets();
  eyeViews(fixture);
  return failures;
}
