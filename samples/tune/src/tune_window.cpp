#include "s3d/tune/tune_window.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include "s3d/comfort/display_profile.h"
#include "s3d/io/image_io.h"
#include "s3d/renderer/scene.h"
#include "s3d/tune/tune_session.h"
#include "tune_panel.h"
#include "s3d/vk/check.h"
#include "s3d/vk/resources.h"
#include "s3d/vk/unique.h"

namespace s3d::tune {
namespace {

std::string lastGlfwError;  // GLFW reports errors through a callback; the latest one explains a failure

void onGlfwError(int code, const char* description) {
  lastGlfwError = std::string(description ? description : "unknown") + " (GLFW error " + std::to_string(code) + ")";
}

// glfwInit .. glfwTerminate.
struct Glfw {
  Glfw() {
    glfwSetErrorCallback(&onGlfwError);
    if (!glfwInit())
      throw NoDisplayError("cannot open a window: " + lastGlfwError +
                           "; run on a desktop or under a virtual display (xvfb-run -a s3d tune ...)");
  }
  ~Glfw() { glfwTerminate(); }
  Glfw(const Glfw&) = delete;
  Glfw& operator=(const Glfw&) = delete;
};

struct WindowDeleter {
  void operator()(GLFWwindow* window) const { glfwDestroyWindow(window); }
};

void checkImGuiVk(VkResult result) {
  if (result != VK_SUCCESS) vk::check(result, "Dear ImGui Vulkan backend");
}

// One image memory barrier (synchronization2) on a raw image: the swapchain's images are not vk::Images.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 srcStage,
                  VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = srcStage;
  barrier.srcAccessMask = srcAccess;
  barrier.dstStageMask = dstStage;
  barrier.dstAccessMask = dstAccess;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

// Where the view goes in a window of `extent`: top left, left of the panel, 1:1 when it fits (so a screenshot's
// view pixels are the rendered pixels), else scaled down keeping its aspect ratio.
VkRect2D viewRect(VkExtent2D extent, std::uint32_t viewWidth, std::uint32_t viewHeight) {
  const int available = int(extent.width) - kPanelWidth;
  if (available <= 0 || extent.height == 0) return {{0, 0}, {0, 0}};
  const double scale = std::min({1.0, double(available) / viewWidth, double(extent.height) / viewHeight});
  return {{0, 0}, {std::max(1u, std::uint32_t(viewWidth * scale)), std::max(1u, std::uint32_t(viewHeight * scale))}};
}

// The swapchain, the render pass Dear ImGui draws in, and one frame's commands: the view is uploaded, blitted into
// the swapchain image, the panel drawn over the rest, and (on request) the whole image read back.
class Presenter {
 public:
  Presenter(vk::Context& context, GLFWwindow* window) : context_(context), window_(window) {
    const VkDevice device = context.device();
    chooseSurfaceFormat();
    createRenderPass();
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = context.queueFamily();
    VkCommandPool pool = VK_NULL_HANDLE;
    S3D_VK_CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &pool));
    commandPool_ = vk::Unique<VkCommandPool>(device, pool, vkDestroyCommandPool);
    VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocInfo.commandPool = commandPool_;
    allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocInfo.commandBufferCount = 1;
    S3D_VK_CHECK(vkAllocateCommandBuffers(device, &allocInfo, &commandBuffer_));
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore = VK_NULL_HANDLE;
    S3D_VK_CHECK(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &semaphore));
    imageAvailable_ = vk::Unique<VkSemaphore>(device, semaphore, vkDestroySemaphore);
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    S3D_VK_CHECK(vkCreateFence(device, &fenceInfo, nullptr, &fence));
    frameDone_ = vk::Unique<VkFence>(device, fence, vkDestroyFence);
    createSwapchain();
  }

  ~Presenter() {
    vkDeviceWaitIdle(context_.device());
    destroySwapchain();
  }
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  VkRenderPass renderPass() const { return renderPass_; }
  std::uint32_t imageCount() const { return std::uint32_t(images_.size()); }
  std::uint32_t minImageCount() const { return minImageCount_; }

  // Shows `view` and the panel; with `screenshot`, returns the whole window's image as shown.
  std::optional<ImageRGBA8> draw(const ImageRGBA8& view, ImDrawData* panel, bool screenshot) {
    int framebufferWidth = 0, framebufferHeight = 0;
    glfwGetFramebufferSize(window_, &framebufferWidth, &framebufferHeight);
    if (framebufferWidth <= 0 || framebufferHeight <= 0) return std::nullopt;  // minimized
    if (std::uint32_t(framebufferWidth) != extent_.width || std::uint32_t(framebufferHeight) != extent_.height)
      recreateSwapchain();

    std::uint32_t index = 0;
    VkResult acquired = vkAcquireNextImageKHR(context_.device(), swapchain_, UINT64_MAX, imageAvailable_, VK_NULL_HANDLE, &index);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
      recreateSwapchain();
      acquired = vkAcquireNextImageKHR(context_.device(), swapchain_, UINT64_MAX, imageAvailable_, VK_NULL_HANDLE, &index);
    }
    if (acquired != VK_SUBOPTIMAL_KHR) vk::check(acquired, "vkAcquireNextImageKHR");

    uploadView(view);
    record(index, panel, screenshot);
    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;  // the first write is the clear
    const VkSemaphore renderDone = renderDone_[index];
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 1;
    const VkSemaphore available = imageAvailable_;
    submit.pWaitSemaphores = &available;
    submit.pWaitDstStageMask = &waitStage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commandBuffer_;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &renderDone;
    S3D_VK_CHECK(vkQueueSubmit(context_.queue(), 1, &submit, frameDone_));
    const VkFence fence = frameDone_;
    S3D_VK_CHECK(vkWaitForFences(context_.device(), 1, &fence, VK_TRUE, UINT64_MAX));
    S3D_VK_CHECK(vkResetFences(context_.device(), 1, &fence));

    std::optional<ImageRGBA8> shot;
    if (screenshot) shot = readScreenshot();

    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &renderDone;
    present.swapchainCount = 1;
    const VkSwapchainKHR swapchain = swapchain_;
    present.pSwapchains = &swapchain;
    present.pImageIndices = &index;
    const VkResult presented = vkQueuePresentKHR(context_.queue(), &present);
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) recreateSwapchain();
    else vk::check(presented, "vkQueuePresentKHR");
    return shot;
  }

 private:
  void chooseSurfaceFormat() {
    std::uint32_t count = 0;
    S3D_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(context_.physicalDevice(), context_.surface(), &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    S3D_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(context_.physicalDevice(), context_.surface(), &count, formats.data()));
    if (formats.empty()) throw NoDisplayError("the window surface offers no formats");
    // UNORM: the view's bytes are already sRGB-encoded and must reach the screen unchanged (an _SRGB swapchain
    // would encode them a second time), and Dear ImGui's colours are meant for UNORM targets too.
    surfaceFormat_ = formats.front();
    for (const VkSurfaceFormatKHR& format : formats)
      if ((format.format == VK_FORMAT_B8G8R8A8_UNORM || format.format == VK_FORMAT_R8G8B8A8_UNORM) &&
          format.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
        surfaceFormat_ = format;
        break;
      }
    if (surfaceFormat_.format != VK_FORMAT_B8G8R8A8_UNORM && surfaceFormat_.format != VK_FORMAT_R8G8B8A8_UNORM)
      std::cerr << "s3d: warning: the window has no 8-bit UNORM format; colours may look different\n";
  }

  void createRenderPass() {
    VkAttachmentDescription color{};
    color.format = surfaceFormat_.format;
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the view blitted before the panel draws over it
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;
    // Clear and blit before the panel; the panel before the screenshot's copy.
    VkSubpassDependency dependencies[2]{};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependencies[0].srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &color;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 2;
    info.pDependencies = dependencies;
    VkRenderPass renderPass = VK_NULL_HANDLE;
    S3D_VK_CHECK(vkCreateRenderPass(context_.device(), &info, nullptr, &renderPass));
    renderPass_ = vk::Unique<VkRenderPass>(context_.device(), renderPass, vkDestroyRenderPass);
  }

  void createSwapchain() {
    const VkDevice device = context_.device();
    VkSurfaceCapabilitiesKHR capabilities{};
    S3D_VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physicalDevice(), context_.surface(), &capabilities));
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if ((capabilities.supportedUsageFlags & usage) != usage)
      throw NoDisplayError("the window's swapchain images cannot be copied to and from (transfer usage missing)");
    int width = 0, height = 0;
    glfwGetFramebufferSize(window_, &width, &height);
    extent_ = capabilities.currentExtent;
    if (extent_.width == UINT32_MAX) {
      extent_.width = std::clamp(std::uint32_t(width), capabilities.minImageExtent.width, capabilities.maxImageExtent.width);
      extent_.height = std::clamp(std::uint32_t(height), capabilities.minImageExtent.height, capabilities.maxImageExtent.height);
    }
    minImageCount_ = std::max(2u, capabilities.minImageCount);
    if (capabilities.maxImageCount > 0) minImageCount_ = std::min(minImageCount_, capabilities.maxImageCount);

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = context_.surface();
    info.minImageCount = minImageCount_;
    info.imageFormat = surfaceFormat_.format;
    info.imageColorSpace = surfaceFormat_.colorSpace;
    info.imageExtent = extent_;
    info.imageArrayLayers = 1;
    info.imageUsage = usage;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = capabilities.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // always supported
    info.clipped = VK_TRUE;
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    S3D_VK_CHECK(vkCreateSwapchainKHR(device, &info, nullptr, &swapchain));
    swapchain_ = vk::Unique<VkSwapchainKHR>(device, swapchain, vkDestroySwapchainKHR);

    std::uint32_t count = 0;
    S3D_VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, nullptr));
    images_.resize(count);
    S3D_VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, images_.data()));
    for (VkImage image : images_) {
      VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
      viewInfo.image = image;
      viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
      viewInfo.format = surfaceFormat_.format;
      viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      VkImageView view = VK_NULL_HANDLE;
      S3D_VK_CHECK(vkCreateImageView(device, &viewInfo, nullptr, &view));
      imageViews_.emplace_back(device, view, vkDestroyImageView);
      VkFramebufferCreateInfo framebufferInfo{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
      framebufferInfo.renderPass = renderPass_;
      framebufferInfo.attachmentCount = 1;
      framebufferInfo.pAttachments = &view;
      framebufferInfo.width = extent_.width;
      framebufferInfo.height = extent_.height;
      framebufferInfo.layers = 1;
      VkFramebuffer framebuffer = VK_NULL_HANDLE;
      S3D_VK_CHECK(vkCreateFramebuffer(device, &framebufferInfo, nullptr, &framebuffer));
      framebuffers_.emplace_back(device, framebuffer, vkDestroyFramebuffer);
      // One per image: presentation may still wait on an image's semaphore when the next frame starts.
      VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
      VkSemaphore semaphore = VK_NULL_HANDLE;
      S3D_VK_CHECK(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &semaphore));
      renderDone_.emplace_back(device, semaphore, vkDestroySemaphore);
    }
    screenshotBuffer_ = vk::createBuffer(context_, VkDeviceSize(extent_.width) * extent_.height * 4,
                                         VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryLocation::HostVisible);
  }

  void destroySwapchain() {
    screenshotBuffer_ = {};
    renderDone_.clear();
    framebuffers_.clear();
    imageViews_.clear();
    images_.clear();
    swapchain_.reset();
  }

  void recreateSwapchain() {
    S3D_VK_CHECK(vkDeviceWaitIdle(context_.device()));
    destroySwapchain();
    createSwapchain();
  }

  void uploadView(const ImageRGBA8& view) {
    if (!viewImage_.image || viewImage_.width != view.width || viewImage_.height != view.height) {
      viewImage_ = vk::createImage(context_, VK_FORMAT_R8G8B8A8_UNORM, view.width, view.height,
                                   VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                       VK_IMAGE_USAGE_SAMPLED_BIT);  // vk::createImage also makes a view
      viewStaging_ = vk::createBuffer(context_, VkDeviceSize(view.pixels.size()), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                      vk::MemoryLocation::HostVisible);
    }
    std::memcpy(viewStaging_.mapped, view.pixels.data(), view.pixels.size());
  }

  void record(std::uint32_t index, ImDrawData* panel, bool screenshot) {
    const VkCommandBuffer cmd = commandBuffer_;
    const VkImage target = images_[index];
    S3D_VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    S3D_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));

    // The view: staging buffer -> view image.
    imageBarrier(cmd, viewImage_.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {viewImage_.width, viewImage_.height, 1};
    vkCmdCopyBufferToImage(cmd, viewStaging_.buffer, viewImage_.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    imageBarrier(cmd, viewImage_.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT);

    // The window: background, then the view blitted into its rectangle (format conversion, 1:1 exact).
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                 VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const VkClearColorValue background{{0.08f, 0.08f, 0.09f, 1.0f}};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &background, 1, &range);
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                 VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const VkRect2D rect = viewRect(extent_, viewImage_.width, viewImage_.height);
    if (rect.extent.width > 0) {
      VkImageBlit blit{};
      blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      blit.srcOffsets[1] = {std::int32_t(viewImage_.width), std::int32_t(viewImage_.height), 1};
      blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      blit.dstOffsets[0] = {rect.offset.x, rect.offset.y, 0};
      blit.dstOffsets[1] = {rect.offset.x + std::int32_t(rect.extent.width), rect.offset.y + std::int32_t(rect.extent.height), 1};
      const bool oneToOne = rect.extent.width == viewImage_.width && rect.extent.height == viewImage_.height;
      vkCmdBlitImage(cmd, viewImage_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, oneToOne ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
    }

    // The panel (render pass: transfer-dst -> attachment -> present-src).
    VkRenderPassBeginInfo passInfo{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    passInfo.renderPass = renderPass_;
    passInfo.framebuffer = framebuffers_[index];
    passInfo.renderArea = {{0, 0}, extent_};
    vkCmdBeginRenderPass(cmd, &passInfo, VK_SUBPASS_CONTENTS_INLINE);
    if (panel) ImGui_ImplVulkan_RenderDrawData(panel, cmd);
    vkCmdEndRenderPass(cmd);

    if (screenshot) {
      imageBarrier(cmd, target, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COPY_BIT,
                   VK_ACCESS_2_TRANSFER_READ_BIT);
      VkBufferImageCopy back{};
      back.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      back.imageExtent = {extent_.width, extent_.height, 1};
      vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, screenshotBuffer_.buffer, 1, &back);
      imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE);
      VkBufferMemoryBarrier2 hostRead{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
      hostRead.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
      hostRead.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
      hostRead.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
      hostRead.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
      hostRead.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      hostRead.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      hostRead.buffer = screenshotBuffer_.buffer;
      hostRead.size = VK_WHOLE_SIZE;
      VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
      dependency.bufferMemoryBarrierCount = 1;
      dependency.pBufferMemoryBarriers = &hostRead;
      vkCmdPipelineBarrier2(cmd, &dependency);
    }
    S3D_VK_CHECK(vkEndCommandBuffer(cmd));
  }

  ImageRGBA8 readScreenshot() const {
    ImageRGBA8 image(extent_.width, extent_.height);
    std::memcpy(image.pixels.data(), screenshotBuffer_.mapped, image.pixels.size());
    const bool bgra = surfaceFormat_.format == VK_FORMAT_B8G8R8A8_UNORM || surfaceFormat_.format == VK_FORMAT_B8G8R8A8_SRGB;
    for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
      if (bgra) std::swap(image.pixels[i], image.pixels[i + 2]);
      image.pixels[i + 3] = 255;  // the window is opaque
    }
    return image;
  }

  vk::Context& context_;
  GLFWwindow* window_;
  VkSurfaceFormatKHR surfaceFormat_{};
  vk::Unique<VkRenderPass> renderPass_;
  vk::Unique<VkCommandPool> commandPool_;
  VkCommandBuffer commandBuffer_ = VK_NULL_HANDLE;  // freed with its pool
  vk::Unique<VkSemaphore> imageAvailable_;
  vk::Unique<VkFence> frameDone_;
  VkExtent2D extent_{};
  std::uint32_t minImageCount_ = 2;
  vk::Unique<VkSwapchainKHR> swapchain_;
  std::vector<VkImage> images_;  // owned by the swapchain
  std::vector<vk::Unique<VkImageView>> imageViews_;
  std::vector<vk::Unique<VkFramebuffer>> framebuffers_;
  std::vector<vk::Unique<VkSemaphore>> renderDone_;
  vk::Buffer screenshotBuffer_;
  vk::Image viewImage_;
  vk::Buffer viewStaging_;
};

// Dear ImGui with its GLFW and Vulkan backends, set up and torn down in order.
class ImGuiLayer {
 public:
  ImGuiLayer(vk::Context& context, GLFWwindow* window, const Presenter& presenter) : device_(context.device()) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini: every run starts with the same layout
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window, true);
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    poolInfo.maxSets = 16;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    S3D_VK_CHECK(vkCreateDescriptorPool(device_, &poolInfo, nullptr, &pool));
    descriptorPool_ = vk::Unique<VkDescriptorPool>(device_, pool, vkDestroyDescriptorPool);
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = context.instance();
    info.PhysicalDevice = context.physicalDevice();
    info.Device = context.device();
    info.QueueFamily = context.queueFamily();
    info.Queue = context.queue();
    info.DescriptorPool = descriptorPool_;
    info.MinImageCount = presenter.minImageCount();
    info.ImageCount = std::max(presenter.imageCount(), presenter.minImageCount());
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = &checkImGuiVk;
    ImGui_ImplVulkan_Init(&info, presenter.renderPass());
    context.submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
  }
  ~ImGuiLayer() {
    vkDeviceWaitIdle(device_);
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

 private:
  VkDevice device_;
  vk::Unique<VkDescriptorPool> descriptorPool_;
};

// Keyboard and mouse into one frame's input, unless the panel has them.
FrameInput windowInput(GLFWwindow* window, glm::dvec2& lastCursor) {
  FrameInput input;
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureKeyboard) {
    input.forward = glfwGetKey(window, GLFW_KEY_W) == GLFW_PRESS;
    input.back = glfwGetKey(window, GLFW_KEY_S) == GLFW_PRESS;
    input.left = glfwGetKey(window, GLFW_KEY_A) == GLFW_PRESS;
    input.right = glfwGetKey(window, GLFW_KEY_D) == GLFW_PRESS;
    input.down = glfwGetKey(window, GLFW_KEY_Q) == GLFW_PRESS;
    input.up = glfwGetKey(window, GLFW_KEY_E) == GLFW_PRESS;
  }
  glm::dvec2 cursor;
  glfwGetCursorPos(window, &cursor.x, &cursor.y);
  if (!io.WantCaptureMouse && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS)
    input.lookPx = glm::vec2(cursor - lastCursor);
  lastCursor = cursor;
  return input;
}

}  // namespace

TuneWindowResult runTuneWindow(const TuneWindowOptions& options) {
  validate(options.state.settings);
  const std::vector<ScriptCommand> script = options.script ? loadScript(*options.script) : std::vector<ScriptCommand>{};
  std::optional<ScriptPlayer> player;
  if (options.script) player.emplace(script);
  const bool scripted = options.script || options.frames;

  Glfw glfw;
  if (!glfwVulkanSupported()) throw NoDisplayError("cannot open a window: GLFW finds no Vulkan loader or surface support");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  const int windowWidth = int(options.width) + kPanelWidth;
  const int windowHeight = std::max(int(options.height), kMinWindowHeight);
  std::unique_ptr<GLFWwindow, WindowDeleter> window(
      glfwCreateWindow(windowWidth, windowHeight, "s3d tune", nullptr, nullptr));
  if (!window) throw NoDisplayError("cannot open a window: " + lastGlfwError);

  vk::ContextOptions contextOptions = options.context;
  std::uint32_t extensionCount = 0;
  const char** extensions = glfwGetRequiredInstanceExtensions(&extensionCount);
  if (!extensions) throw NoDisplayError("cannot open a window: " + lastGlfwError);
  contextOptions.instanceExtensions.assign(extensions, extensions + extensionCount);
  GLFWwindow* rawWindow = window.get();
  contextOptions.createSurface = [rawWindow](VkInstance instance) {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    vk::check(glfwCreateWindowSurface(instance, rawWindow, nullptr, &surface), "glfwCreateWindowSurface");
    return surface;
  };
  vk::Context context(contextOptions);
  TuneWindowResult result;
  result.deviceName = context.deviceName();
  {
    Presenter presenter(context, rawWindow);
    ImGuiLayer imgui(context, rawWindow, presenter);
    TuneSession session(context, options.width, options.height);
    TuneState state = options.state;
    session.loadScene(state);
    PanelState panel;
    std::snprintf(panel.profilePath, sizeof(panel.profilePath), "%s", options.profileFile.string().c_str());
    glm::dvec2 lastCursor(0.0);
    glfwGetCursorPos(rawWindow, &lastCursor.x, &lastCursor.y);
    auto last = std::chrono::steady_clock::now();
    float frameSeconds = kScriptedFrameSeconds;  // wall time of the last frame, at most 0.25 s for the camera
    float measuredSeconds = 0.0f;                 // the same, unclamped, for the panel

    while (!glfwWindowShouldClose(rawWindow)) {
      glfwPollEvents();
      WindowRequests requests;
      FrameInput input = windowInput(rawWindow, lastCursor);
      if (player && !player->finished()) {
        ScriptFrame step = player->next();
        for (const ScriptCommand& command : step.commands) runScriptCommand(session, state, command, requests);
        input = step.input;  // a script drives the frame alone: a stray mouse must not change the result
      }
      const bool lastFrame = options.frames && result.frames + 1 >= *options.frames;
      if (options.screenshot && (lastFrame || requests.quit) && !requests.screenshot) requests.screenshot = options.screenshot;

      const TuneFrame frame = session.renderFrame(state, input, scripted ? kScriptedFrameSeconds : frameSeconds);
      ImGui_ImplVulkan_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      drawPanel(session, state, frame.numbers, panel, result.deviceName, measuredSeconds);
      ImGui::Render();
      const std::optional<ImageRGBA8> shot = presenter.draw(frame.view, ImGui::GetDrawData(), requests.screenshot.has_value());
      if (requests.screenshot) {
        if (!shot) throw std::runtime_error("no screenshot: the window has no area (minimized?)");
        io::writePng(*requests.screenshot, *shot);
      }
      ++result.frames;
      const auto now = std::chrono::steady_clock::now();
      measuredSeconds = std::chrono::duration<float>(now - last).count();
      frameSeconds = std::min(0.25f, measuredSeconds);
      last = now;
      if (requests.quit || lastFrame) break;
    }
  }
  result.validationMessages = context.validationMessages();
  return result;
}

}  // namespace s3d::tune
