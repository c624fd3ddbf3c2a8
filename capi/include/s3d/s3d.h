/* s3d's C API for hosts that bind C (Godot GDExtension, Unity native plugins, C engines): opaque handles, POD
 * parameter structs, error codes plus a per-thread last-error string. Stable within a minor version (0.7).
 * See docs/INTEGRATION.md for the frame sequence and the synchronization contract. */
#ifndef S3D_S3D_H
#define S3D_S3D_H

#include <stdint.h>
#include <vulkan/vulkan.h>

#ifdef __cplusplus
extern "C" {
#endif

#define S3D_API_VERSION_MAJOR 0
#define S3D_API_VERSION_MINOR 7

typedef enum s3d_result {
  S3D_SUCCESS = 0,
  S3D_ERROR_INVALID_ARGUMENT = -1,   /* a parameter, format, size or layout s3d does not accept */
  S3D_ERROR_DEVICE_UNSUPPORTED = -2, /* the device lacks a required feature or extension (named in the message) */
  S3D_ERROR_VULKAN = -3,             /* a Vulkan call failed */
  S3D_ERROR_UNKNOWN = -4
} s3d_result;

/* The message of this thread's last failed call ("" after a success). Valid until the thread's next s3d call.
 * Every function refuses a NULL handle or pointer it needs, an enum value outside its enum, a non-finite or
 * out-of-range float and a size past the device's limits with S3D_ERROR_INVALID_ARGUMENT; the message names the
 * parameter or field. Functions without a result code return 0 / NULL / VK_FORMAT_UNDEFINED and set it too. */
const char* s3d_last_error(void);

/* ---- Device ---- */
uint32_t s3d_required_api_version(void);
uint32_t s3d_required_extension_count(void);
const char* s3d_required_extension(uint32_t index);
uint32_t s3d_required_feature_count(void);
const char* s3d_required_feature(uint32_t index); /* VkPhysicalDeviceVulkan13Features member names */

/* Adds s3d's extensions and features to the host's create info; keep the patch until vkCreateDevice returned. */
typedef struct s3d_device_patch_t* s3d_device_patch;
s3d_result s3d_device_patch_apply(VkPhysicalDevice physical_device, VkDeviceCreateInfo* info, s3d_device_patch* out);
void s3d_device_patch_destroy(s3d_device_patch patch);

typedef struct s3d_host_device {
  VkInstance instance;
  VkPhysicalDevice physical_device;
  VkDevice device;
  uint32_t queue_family;
  VkQueue queue;                          /* used only while creating passes (uploads), never per frame */
  const VkAllocationCallbacks* allocator; /* may be NULL */
  VkPipelineCache pipeline_cache;         /* may be VK_NULL_HANDLE */
  const VkDeviceCreateInfo* create_info;  /* may be NULL; when given, enabled features are checked too */
} s3d_host_device;

typedef struct s3d_context_t* s3d_context;
s3d_result s3d_context_create(const s3d_host_device* host, s3d_context* out);
void s3d_context_destroy(s3d_context context);

/* ---- Stereo pass on the host's images ---- */
typedef enum s3d_output {
  S3D_OUTPUT_TWO_EYES = 0,
  S3D_OUTPUT_SIDE_BY_SIDE_HALF = 1,
  S3D_OUTPUT_SIDE_BY_SIDE_FULL = 2,
  S3D_OUTPUT_TOP_BOTTOM_HALF = 3,
  S3D_OUTPUT_TOP_BOTTOM_FULL = 4,
  S3D_OUTPUT_ANAGLYPH = 5
} s3d_output;

typedef struct s3d_host_pass_desc {
  uint32_t width;  /* 1 .. the device's maxImageDimension2D; 2 * width within it for S3D_OUTPUT_SIDE_BY_SIDE_FULL */
  uint32_t height; /* likewise; 2 * height for S3D_OUTPUT_TOP_BOTTOM_FULL; half packings need 2 or more */
  VkFormat color_format; /* RGBA8/BGRA8 UNORM or SRGB, RGBA16F, B10G11R11 */
  VkFormat depth_format; /* D32, D24S8, D16, or R32F linear depth */
  s3d_output output;
  int32_t inputs_are_storage; /* 1: RGBA8 UNORM + R32F storage images, read without conversion */
} s3d_host_pass_desc;

/* The displacement methods (docs/DESIGN.md): the host pass below takes seed and search; the stereo frame takes all. */
typedef enum s3d_method {
  S3D_METHOD_SEED = 0,      /* Listing 4.5: taps at 0.5/0.66/1.0 of the separation */
  S3D_METHOD_SEARCH = 1,    /* search_taps taps spread over the separation */
  S3D_METHOD_ITERATIVE = 2, /* fixed-point source search (8-bit colour) */
  S3D_METHOD_FORWARD = 3,   /* z-buffered scatter of every pixel, holes from the background (8-bit colour) */
  /* stereo frame, two eyes, 8-bit colour: search, then the host's raster re-draws the pixels it gets wrong
   * (s3d_stereo_frame_record_hybrid_masks, the host's draw, s3d_stereo_frame_record_hybrid_composite) */
  S3D_METHOD_HYBRID = 4
} s3d_method;

typedef struct s3d_stereo_parameters {
  float max_separation;         /* per-eye displacement at infinity, fraction of the width: 0 .. 0.25 */
  float zero_parallax_distance; /* world units, > 0 */
  float edge_crop;              /* fraction of the width per side, <= 0.25; < 0: = max_separation */
  s3d_method method;
  int32_t search_taps;          /* S3D_METHOD_SEARCH: 1..16 */
  float weapon_depth_offset;    /* first-person push: depth' = offset + scale * depth; offset >= 0, scale > 0 */
  float weapon_depth_scale;     /* (every float here finite) */
} s3d_stereo_parameters;
void s3d_default_stereo_parameters(s3d_stereo_parameters* out);

typedef struct s3d_projection {
  float near_plane; /* > 0 */
  float far_plane;  /* > near_plane unless infinite_far_plane */
  int32_t reversed_z;
  int32_t infinite_far_plane;
  float first_person_depth_range; /* 0 .. < 1; 0: no first-person layer */
  float first_person_near;        /* with a layer: 0 < first_person_near < first_person_far */
  float first_person_far;
} s3d_projection;

typedef struct s3d_host_image {
  VkImage image;
  VkImageView view;
  VkFormat format;
  VkImageLayout layout;        /* current; the image is left in it */
  /* the host's last access (s3d adds barriers), or 0: the host synchronizes, and `layout` must be GENERAL
   * (outputs, storage inputs) or a read-only layout (sampled inputs) */
  VkPipelineStageFlags2 stage;
  VkAccessFlags2 access;
  uint32_t layer; /* the array layer `view` shows: 0, or 0 and 1 for two eyes in one 2-layer array image */
} s3d_host_image;

typedef struct s3d_host_pass_t* s3d_host_pass;
s3d_result s3d_host_pass_create(s3d_context context, const s3d_host_pass_desc* desc, s3d_host_pass* out);
void s3d_host_pass_destroy(s3d_host_pass pass);
VkFormat s3d_host_pass_eye_format(s3d_host_pass pass);
void s3d_host_pass_packed_size(s3d_host_pass pass, uint32_t* width, uint32_t* height);
/* Records into the host's command buffer; left/right for S3D_OUTPUT_TWO_EYES, target otherwise (others NULL). */
s3d_result s3d_host_pass_record(s3d_host_pass pass, VkCommandBuffer cmd, const s3d_host_image* color,
                                const s3d_host_image* depth, const s3d_stereo_parameters* parameters,
                                const s3d_projection* projection, const s3d_host_image* left,
                                const s3d_host_image* right, const s3d_host_image* target);

/* ---- Per-eye views, as OpenXR's XrView reports them (docs/INTEGRATION.md "Per-eye views") ---- */
typedef struct s3d_eye_view {
  float position_x;  /* metres along the center camera's x axis (XrView.pose.position in the head's frame), finite */
  float angle_left;  /* radians (XrFovf), each in (-pi/2, pi/2); angle_left < angle_right, angle_down < angle_up */
  float angle_right;
  float angle_up;
  float angle_down;
} s3d_eye_view;

/* Two parallel eyes of the stereo frame's width x height. Its kernels displace both eyes along rows by one mirrored
 * parallax, so they reproduce converging eyes (a screen's off-axis pair): one vertical field and one horizontal
 * extent for both eyes (within a quarter pixel), the left eye's frustum shifted right of the right eye's by at most
 * a quarter of the width. A headset's parallel or outward-turned frusta are refused, naming left.angle_left. */
typedef struct s3d_eye_views {
  s3d_eye_view left; /* left.position_x < right.position_x; the center image is rendered from their midpoint with
                        the mean of their frusta (s3d_stereo_for_eye_views gives its angles) */
  s3d_eye_view right;
  float world_scale; /* world units per metre, finite, > 0 */
} s3d_eye_views;

/* What the stereo frame derives from eye views: the camera the host renders its center image with, and the
 * parameters its kernels use (for s3d_frame_comfort_input.parameters). */
typedef struct s3d_eye_views_stereo {
  s3d_eye_view center; /* position_x: the eyes' midpoint; angles: the atan of the mean of the eyes' tangents */
  float max_separation;
  float zero_parallax_distance; /* world units */
} s3d_eye_views_stereo;
/* width, height: the stereo frame's (>= 1). Refuses views the stereo frame would refuse, naming the field. */
s3d_result s3d_stereo_for_eye_views(const s3d_eye_views* views, uint32_t width, uint32_t height,
                                    s3d_eye_views_stereo* out);

/* ---- Stereo frame: every method, one description at creation, one dispatch description per frame ----
 * Synchronization and images as the host pass's; recording allocates nothing. With previous_frame_fill, submit the
 * frames in the order they were recorded. */
typedef struct s3d_stereo_frame_desc {
  uint32_t width;  /* the host's colour and depth images; the eyes have this size */
  uint32_t height;
  VkFormat color_format; /* RGBA8/BGRA8 UNORM or SRGB, RGBA16F, B10G11R11 (HDR colour: seed or search) */
  VkFormat depth_format; /* D32, D24S8, D16, or R32F linear depth */
  s3d_output output;
  s3d_method method;
  int32_t search_taps;         /* S3D_METHOD_SEARCH: 1..16 */
  int32_t iterations;          /* S3D_METHOD_ITERATIVE: 1..16 */
  int32_t previous_frame_fill; /* S3D_METHOD_FORWARD: 1 fills holes from the previous frame's eyes */
  float hybrid_budget;         /* S3D_METHOD_HYBRID: the largest share of each eye's pixels the host re-draws, 0..1 */
  int32_t hybrid_cell;         /* S3D_METHOD_HYBRID: pixels per side of the classification's cell, 1 or 2 (each 2x2
                                  block classified once: less time, a few edge pixels left displaced); 0 by the
                                  width (2 from 1280 pixels) */
  float hybrid_score_floor;    /* S3D_METHOD_HYBRID: below a budget of 1, pixels whose expected parallax error in
                                  pixels lies under this are never re-drawn, 0..32 */
} s3d_stereo_frame_desc;
/* Search with 4 taps, two eyes, R8G8B8A8_SRGB colour and D32 depth, hybrid budget 0.6, cell by the width, score
 * floor 0.15; width and height 0 (the host sets them). */
void s3d_default_stereo_frame_desc(s3d_stereo_frame_desc* out);

typedef struct s3d_stereo_frame_dispatch {
  s3d_host_image color;
  s3d_host_image depth;
  s3d_host_image left;   /* S3D_OUTPUT_TWO_EYES: two images, or one 2-layer array image (layer 0 and 1) */
  s3d_host_image right;
  s3d_host_image target; /* packed outputs */
  s3d_projection projection; /* the depth buffer's convention (ignored for R32F linear depth) */
  float max_separation;         /* 0 .. 0.25 of the width */
  float zero_parallax_distance; /* world units, > 0 */
  float edge_crop;              /* fraction of the width per side, <= 0.25; < 0: = max_separation */
  float weapon_depth_offset;    /* first-person push: depth' = offset + scale * depth */
  float weapon_depth_scale;
  /* previous_frame_fill: the center camera (world to view) and its projection, column-major, Vulkan clip space */
  float center_view[16];
  float center_projection[16];
  int32_t camera_cut; /* 1: this frame does not continue the previous one */
  /* NULL: max_separation and zero_parallax_distance as given. Otherwise the eyes' views, from which s3d derives both
   * (as s3d_stereo_for_eye_views; the two fields are then ignored); read during the call only. */
  const s3d_eye_views* eye_views;
  /* S3D_METHOD_HYBRID (center_view and center_projection too): each eye's mask as the depth image the host draws
   * that eye with (D32_SFLOAT, TRANSFER_DST usage, the frame's size; view unused): far where the host re-draws,
   * near elsewhere; barriered from and back to its layout, stage and access (stage 0: TRANSFER_DST_OPTIMAL or
   * GENERAL, the host orders its use after the copy) */
  s3d_host_image left_mask;
  s3d_host_image right_mask;
} s3d_stereo_frame_dispatch;
/* Zero images, s3d's default parameters, identity matrices, projection near 0.1 / far 1000, no eye views. */
void s3d_default_stereo_frame_dispatch(s3d_stereo_frame_dispatch* out);

typedef struct s3d_stereo_frame_t* s3d_stereo_frame;
s3d_result s3d_stereo_frame_create(s3d_context context, const s3d_stereo_frame_desc* desc, s3d_stereo_frame* out);
void s3d_stereo_frame_destroy(s3d_stereo_frame frame);
VkFormat s3d_stereo_frame_eye_format(s3d_stereo_frame frame);
void s3d_stereo_frame_packed_size(s3d_stereo_frame frame, uint32_t* width, uint32_t* height);
s3d_result s3d_stereo_frame_record(s3d_stereo_frame frame, VkCommandBuffer cmd,
                                   const s3d_stereo_frame_dispatch* dispatch);

/* S3D_METHOD_HYBRID, in place of s3d_stereo_frame_record (docs/INTEGRATION.md "The hybrid in a host's renderer"):
 * 1. record_hybrid_masks: the search into the eyes, the masks into left_mask and right_mask, and the eye cameras
 *    the host draws from; 2. the host draws its scene into each eye (load, no clear) with that eye's mask as depth
 *    attachment (load, no clear), depth test LESS (reversed-Z: GREATER): only masked pixels change; 3.
 *    record_hybrid_composite: what follows the host's draw (nothing for two eyes without an overlay). */
typedef struct s3d_eye_cameras {
  float left_view[16]; /* world to view, column-major */
  float left_projection[16]; /* Vulkan clip space, column-major: the center projection shifted off-axis */
  float right_view[16];
  float right_projection[16];
} s3d_eye_cameras;
s3d_result s3d_stereo_frame_record_hybrid_masks(s3d_stereo_frame frame, VkCommandBuffer cmd,
                                                const s3d_stereo_frame_dispatch* dispatch, s3d_eye_cameras* cameras);
s3d_result s3d_stereo_frame_record_hybrid_composite(s3d_stereo_frame frame, VkCommandBuffer cmd,
                                                    const s3d_stereo_frame_dispatch* dispatch);

/* ---- HUD pass: element layers over both eyes at their parallax, faded by the weapon mask ---- */
typedef struct s3d_hud_placement {
  float anchor_x; /* center-view pixel (indices) the pivot lands on, before the eye's offset; finite */
  float anchor_y;
  int32_t pivot_x; /* pixel of the layer placed there */
  int32_t pivot_y;
} s3d_hud_placement;

typedef struct s3d_hud_element_desc {
  const char* name;            /* named in errors */
  s3d_hud_placement placement;
  const uint8_t* pixels;       /* width * height straight-alpha RGBA8, copied and uploaded once; NULL: a host layer */
  uint32_t width; /* 1 .. the device's maxImageDimension2D */
  uint32_t height;
} s3d_hud_element_desc;

typedef struct s3d_hud_pass_desc {
  uint32_t width; /* the eyes: 1 .. the device's maxImageDimension2D */
  uint32_t height;
  int32_t built_in; /* 1: s3d's health and ammo panels and crosshair come first (elements 0, 1, 2) */
  const s3d_hud_element_desc* elements; /* then these, drawn in order (later on top); 16 in all (13 with built_in) */
  uint32_t element_count;
} s3d_hud_pass_desc;

/* One element in one frame: parallax_px and fades_behind_weapon from s3d_frame_comfort_state_compute. */
typedef struct s3d_hud_element_frame {
  float parallax_px; /* the right eye's offset; the left eye's is minus this */
  int32_t fades_behind_weapon;
  int32_t hidden;
} s3d_hud_element_frame;

typedef struct s3d_hud_pass_t* s3d_hud_pass;
s3d_result s3d_hud_pass_create(s3d_context context, const s3d_hud_pass_desc* desc, s3d_hud_pass* out);
void s3d_hud_pass_destroy(s3d_hud_pass pass);
uint32_t s3d_hud_pass_element_count(s3d_hud_pass pass);
/* frames: one per element; host_layers: the host layers' images in element order (RGBA8/BGRA8 UNORM, sampled);
 * left/right: R8G8B8A8_UNORM storage eyes whose alpha is the weapon mask. Same synchronization as the stereo pass. */
s3d_result s3d_hud_pass_record(s3d_hud_pass pass, VkCommandBuffer cmd, const s3d_hud_element_frame* frames,
                               uint32_t frame_count, const s3d_host_image* host_layers, uint32_t host_layer_count,
                               const s3d_host_image* left, const s3d_host_image* right);
/* s3d_host_pass_record with the HUD drawn into the eyes before they are packed (for packed outputs). */
s3d_result s3d_host_pass_record_with_hud(s3d_host_pass pass, VkCommandBuffer cmd, const s3d_host_image* color,
                                         const s3d_host_image* depth, const s3d_stereo_parameters* parameters,
                                         const s3d_projection* projection, const s3d_host_image* left,
                                         const s3d_host_image* right, const s3d_host_image* target, s3d_hud_pass hud,
                                         const s3d_hud_element_frame* frames, uint32_t frame_count,
                                         const s3d_host_image* host_layers, uint32_t host_layer_count);

/* ---- Per-frame comfort ---- */
/* Distance (finite, >= 0) to the first world surface along the ray within max_distance; return 0 for no hit. */
typedef int32_t (*s3d_ray_cast)(void* user, const float origin[3], const float direction[3], float max_distance,
                                float* distance);

typedef struct s3d_frame_comfort_input {
  float camera_position[3];
  float camera_aim[3];  /* normalized view axis (length 1 within 1e-3) */
  float camera_near;    /* > 0; every float of this struct finite */
  s3d_ray_cast ray_cast; /* may be NULL */
  void* ray_cast_user;
  s3d_stereo_parameters parameters;
  uint32_t width;           /* of the eyes, >= 1 */
  float crosshair_distance; /* > 0 */
  float crosshair_margin;   /* >= 0 */
  uint64_t weapon_pixels; /* 0: no weapon in view */
  float weapon_nearest_depth; /* with a weapon: 0 < nearest <= farthest */
  float weapon_farthest_depth;
  int32_t has_nearest_world_depth;
  float nearest_world_depth; /* > 0 */
  const float* hud_depths; /* hud_count element depths, each > 0 */
  uint32_t hud_count;
  int32_t allow_negative_parallax;
} s3d_frame_comfort_input;

typedef struct s3d_hud_element_state {
  float depth;
  float parallax_px; /* the right eye's offset (the left eye's is minus this) */
  int32_t fades_behind_weapon;
} s3d_hud_element_state;

typedef struct s3d_frame_comfort_state {
  s3d_stereo_parameters parameters; /* push and zero-parallax distance applied */
  int32_t weapon_pushed;
  int32_t zero_parallax_limited;
  int32_t crosshair_hit_world;
  s3d_hud_element_state crosshair;
} s3d_frame_comfort_state;

/* hud_states: hud_count entries written in the order of hud_depths (may be NULL when hud_count is 0). */
s3d_result s3d_frame_comfort_state_compute(const s3d_frame_comfort_input* input, s3d_frame_comfort_state* out,
                                           s3d_hud_element_state* hud_states);

/* ---- Disparity budget (per display; one controller per view stream, it smooths over frames) ---- */
typedef struct s3d_display {
  float screen_width_meters;     /* a flat screen: the image's width on it, (0, 100] (ignored for a head-mounted display) */
  float viewing_distance_meters; /* eyes to screen, (0, 100]; a head-mounted display: its focal distance */
  float interocular_meters;      /* 0.04 .. 0.08 */
  float field_of_view_degrees;   /* a head-mounted display: horizontal field of view, (0, 170), its virtual screen
                                    at most 100 m wide; 0: a flat screen */
} s3d_display;

typedef struct s3d_budget_controller_t* s3d_budget_controller;
/* The 1-degree rule's budget for the display; allow_negative_parallax must match the frames' setting. */
s3d_result s3d_budget_controller_create(const s3d_display* display, int32_t allow_negative_parallax,
                                        s3d_budget_controller* out);
void s3d_budget_controller_destroy(s3d_budget_controller controller);

/* The frame's linear depth as the stereo pass reads it (the host's reduction, or s3d's DepthRangePass in C++):
 * nearest and farthest finite positive depth, the count of sky (infinite) pixels, and optionally a histogram of
 * any fixed binning (the same every frame) for the cut detector. A range without the weapon gets the pushed
 * weapon added from s3d_frame_comfort_input's weapon fields. */
typedef struct s3d_depth_range {
  float nearest;  /* > 0, <= farthest (finite); > farthest when no pixel is finite; never NaN */
  float farthest;
  uint64_t sky_pixels;
  const uint32_t* histogram; /* may be NULL */
  uint32_t histogram_bins;
} s3d_depth_range;

/* The frame's depth range on the GPU from the host's depth buffer as it is (C++: stereo::DepthRangePass::
 * recordHost): D32, D24S8 or D16 linearized with the projection and the weapon push as the stereo frame reads
 * them, or R32F linear depth. Made once per view stream; recording allocates nothing. Synchronization: as the
 * stereo frame's inputs (a stage in the s3d_host_image: s3d barriers it into a readable layout and back; stage
 * NONE: it must already be in a layout a compute shader samples). */
typedef struct s3d_depth_reduction_t* s3d_depth_reduction;
s3d_result s3d_depth_reduction_create(s3d_context context, s3d_depth_reduction* out);
void s3d_depth_reduction_destroy(s3d_depth_reduction reduction);
/* Records the reduction of `depth` (width x height) into cmd. */
s3d_result s3d_depth_reduction_record(s3d_depth_reduction reduction, VkCommandBuffer cmd, const s3d_host_image* depth,
                                      uint32_t width, uint32_t height, const s3d_projection* projection,
                                      float weapon_depth_offset, float weapon_depth_scale);
/* The range of the last recorded reduction, once its submission has completed: out->histogram points into the
 * reduction's own storage, valid until the next call on it. */
s3d_result s3d_depth_reduction_result(s3d_depth_reduction reduction, s3d_depth_range* out);

typedef struct s3d_frame_budget {
  s3d_budget_controller controller;
  s3d_depth_range depth;
  float frame_seconds;             /* this frame's duration (> 0) */
  int32_t camera_cut;              /* 1: jump to the target without a ramp */
  int32_t receding;                /* 1: the camera moves away from what it sees: more depth is followed at once */
  int32_t has_anticipated_nearest; /* 1: a nearer surface is expected soon (e.g. ray casts ahead) */
  float anticipated_nearest;       /* > 0 */
} s3d_frame_budget;

typedef struct s3d_budget_choice {
  int32_t chosen; /* 0: the range had no pixel, the host's parameters were kept and the fields below are 0 */
  float max_separation; /* as in s3d_frame_comfort_state.parameters */
  float zero_parallax_distance;
  float target_max_separation; /* what this frame alone asks for */
  float target_zero_parallax_distance;
  float used_share;   /* of the budget's usable span, by the frame's depth range */
  int32_t cut;        /* reset without a ramp (first frame, camera_cut, or the histogram changed) */
  int32_t forced;     /* a hard rule moved a parameter by more than the per-frame bound */
  float crossed_fraction;   /* the budget, as fractions of the width between the eyes */
  float uncrossed_fraction;
} s3d_budget_choice;

/* s3d_frame_comfort_state_compute with the disparity budget: out->parameters gets the controller's
 * max_separation and zero_parallax_distance; choice (may be NULL) says what it chose. */
s3d_result s3d_frame_comfort_state_compute_budgeted(const s3d_frame_comfort_input* input,
                                                    const s3d_frame_budget* budget, s3d_frame_comfort_state* out,
                                                    s3d_hud_element_state* hud_states, s3d_budget_choice* choice);

/* ---- Host comfort frame: the stereo frame with its comfort rules in one object (C++: comfort::HostComfortFrame;
 * docs/INTEGRATION.md section 4). Per frame: s3d_host_comfort_frame_update (CPU: the comfort state, which the HUD
 * needs before its overlay is made), then s3d_host_comfort_frame_record (the frame's depth reduction of
 * dispatch.depth into its slot, then the stereo frame). The slot's reduction is read back by the slot's next update,
 * frames_in_flight frames later: the budget follows the depth of that frame; until then it waits (the host's
 * parameters, or the controller's last choice). Synchronization: the reduction and the stereo frame each barrier the
 * depth image from its stated layout, stage and access and back, the reduction first (stage 0: both read it in its
 * layout, which must be one a compute shader samples). Recording creates no Vulkan object. ---- */
typedef struct s3d_host_comfort_frame_desc {
  s3d_stereo_frame_desc stereo;
  const s3d_display* display; /* the disparity budget's display, read during create; NULL: no budget, the host's
                                 max_separation and zero_parallax_distance as given (no-negative-parallax rules on) */
  int32_t allow_negative_parallax;
  uint32_t frames_in_flight; /* the host's frames in flight, >= 1: that many depth reductions */
} s3d_host_comfort_frame_desc;

typedef struct s3d_host_comfort_input {
  uint32_t frame_slot; /* the host's frame-in-flight index, < frames_in_flight; the slot's previous submission has
                          completed (the host's fence wait before reusing its command buffer) */
  /* The host's frame: width must be the frame's, allow_negative_parallax the description's; parameters: the method
   * fields are ignored (the description's). Without has_nearest_world_depth the reduction's nearest depth. */
  s3d_frame_comfort_input frame;
  float frame_seconds;             /* this frame's duration, > 0 */
  int32_t camera_cut;              /* 1: the budget jumps to its target without a ramp */
  int32_t receding;                /* 1: the camera moves away from what it sees */
  int32_t has_anticipated_nearest; /* 1: a nearer surface is expected soon */
  float anticipated_nearest;       /* > 0 */
} s3d_host_comfort_input;

typedef struct s3d_host_comfort_frame_t* s3d_host_comfort_frame;
s3d_result s3d_host_comfort_frame_create(s3d_context context, const s3d_host_comfort_frame_desc* desc,
                                         s3d_host_comfort_frame* out);
void s3d_host_comfort_frame_destroy(s3d_host_comfort_frame frame);
VkFormat s3d_host_comfort_frame_eye_format(s3d_host_comfort_frame frame);
/* The frame's comfort state into out, hud_states (frame.hud_count entries; may be NULL when 0) and choice (may be
 * NULL; chosen 0 without a budget or before the slot's first reduction). */
s3d_result s3d_host_comfort_frame_update(s3d_host_comfort_frame frame, const s3d_host_comfort_input* input,
                                         s3d_frame_comfort_state* out, s3d_hud_element_state* hud_states,
                                         s3d_budget_choice* choice);
/* After this frame's update: the dispatch's max_separation, zero_parallax_distance, weapon_depth_offset and
 * weapon_depth_scale are replaced by the state's; eye_views must be NULL. */
s3d_result s3d_host_comfort_frame_record(s3d_host_comfort_frame frame, VkCommandBuffer cmd,
                                         const s3d_stereo_frame_dispatch* dispatch);
/* S3D_METHOD_HYBRID, in place of s3d_host_comfort_frame_record: as s3d_stereo_frame_record_hybrid_masks (with the
 * reduction first) and s3d_stereo_frame_record_hybrid_composite. */
s3d_result s3d_host_comfort_frame_record_hybrid_masks(s3d_host_comfort_frame frame, VkCommandBuffer cmd,
                                                      const s3d_stereo_frame_dispatch* dispatch,
                                                      s3d_eye_cameras* cameras);
s3d_result s3d_host_comfort_frame_record_hybrid_composite(s3d_host_comfort_frame frame, VkCommandBuffer cmd,
                                                          const s3d_stereo_frame_dispatch* dispatch);

#ifdef __cplusplus
}
#endif

#endif /* S3D_S3D_H */
