// Every public header s3d installs for a host, compiled in this consumer's strict warnings (-Werror).
#include <s3d/camera.h>
#include <s3d/comfort/comfort_report.h>
#include <s3d/comfort/crosshair.h>
#include <s3d/comfort/display_profile.h>
#include <s3d/comfort/frame_comfort_state.h>
#include <s3d/comfort/world_queries.h>
#include <s3d/hud/crosshair.h>
#include <s3d/hud/hud_layers.h>
#include <s3d/hud/hud_pass.h>
#include <s3d/hud/hud_pass_shared.h>
#include <s3d/hud/overlay.h>
#include <s3d/stereo/host_stereo_pass.h>
#include <s3d/stereo/output_formats.h>
#include <s3d/stereo/stereo.h>
#include <s3d/stereo/stereo_pass.h>
#include <s3d/vk/context.h>
#include <s3d/vk/resources.h>
