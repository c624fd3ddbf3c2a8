/* What test_capi.c sets up for the argument checks (test_capi_arguments.c): a patched device, its context, an
 * RGBA8 + R32F two-eye pass, a one-element HUD pass of the same size, a command buffer being recorded and valid
 * images for every slot. */
#ifndef S3D_TEST_CAPI_FIXTURE_H
#define S3D_TEST_CAPI_FIXTURE_H

#include "s3d/s3d.h"

typedef struct capi_fixture {
  VkPhysicalDevice physical;
  s3d_host_device host; /* the patched device's, adopted as `context` */
  VkDeviceCreateInfo* device_info;
  s3d_context context;
  s3d_host_pass pass;
  s3d_hud_pass hud;
  VkCommandBuffer cmd;
  s3d_host_image color, depth, left, right;
} capi_fixture;

/* Every refusal the C API owes a careless caller; returns the number of failed checks. */
int capi_argument_checks(const capi_fixture* fixture);

#endif
