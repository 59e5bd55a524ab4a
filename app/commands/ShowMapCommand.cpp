// `reftrack show-map`: a picture of a reference map — every reference image with the corners of
// its map points, and the 3D points with every reference camera — in a window, or as a PNG.
// glad before GLFW: GLFW must not pull in the system GL header.
#include <glad/gl.h>
// clang-format off
#include <GLFW/glfw3.h>
// clang-format on

#include <cstdio>
#include <fstream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/commands/Commands.hpp"
#include "app/mapview/MapPicture.hpp"
#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "render/context/GlfwWindowContext.hpp"
#include "render/gl/Texture2D.hpp"

namespace reftrack::app {

namespace {

struct ShowMapOptions {
  std::string map, screenshot;
  bool headless = false;
};

void writePng(const cv::Mat& picture, const std::string& path) {
  std::vector<uchar> png;
  if (!cv::imencode(".png", picture, png)) throw Error("cannot encode the map picture as PNG");
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    if (!out) throw Error("cannot write screenshot '" + path + "'");
  });
}

// Shows the picture in a GLFW window (scaled to fit, aspect kept) until closed or Esc/Q.
void showInWindow(const cv::Mat& picture, const std::string& title) {
  render::WindowOptions options;
  options.title = title;
  const double fit = std::min(1.0, std::min(1600.0 / picture.cols, 1000.0 / picture.rows));
  options.size =
      cv::Size(static_cast<int>(picture.cols * fit), static_cast<int>(picture.rows * fit));
  render::GlfwWindowContext window(options);
  render::Texture2D texture;
  texture.upload(picture, false);
  GLuint framebuffer = 0;
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glFramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture.id(), 0);
  while (!window.shouldClose()) {
    window.pollEvents();
    if (glfwGetKey(window.window(), GLFW_KEY_ESCAPE) == GLFW_PRESS ||
        glfwGetKey(window.window(), GLFW_KEY_Q) == GLFW_PRESS)
      window.setShouldClose(true);
    const cv::Size fb = window.framebufferSize();
    const double scale = std::min(static_cast<double>(fb.width) / picture.cols,
                                  static_cast<double>(fb.height) / picture.rows);
    const int w = static_cast<int>(picture.cols * scale),
              h = static_cast<int>(picture.rows * scale);
    const int x = (fb.width - w) / 2, y = (fb.height - h) / 2;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glViewport(0, 0, fb.width, fb.height);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    // Texture row 0 is the image top; the window's row 0 is its bottom: flip while blitting.
    glBlitFramebuffer(0, 0, picture.cols, picture.rows, x, y + h, x + w, y, GL_COLOR_BUFFER_BIT,
                      GL_LINEAR);
    window.swapBuffers();
  }
  glDeleteFramebuffers(1, &framebuffer);
}

void runShowMap(const ShowMapOptions& o) {
  const MultiReferenceMap map = MultiReferenceMap::load(o.map);
  const cv::Mat picture = drawMapPicture(map);
  if (!o.screenshot.empty()) {
    writePng(picture, o.screenshot);
    std::size_t corners = 0;
    for (const ReferenceView& v : map.views) corners += v.corners.size();
    std::printf("wrote %s (%dx%d): %d references, %zu points, %zu corners\n", o.screenshot.c_str(),
                picture.cols, picture.rows, map.size(), map.points.size(), corners);
  }
  if (!o.headless) showInWindow(picture, "reftrack map: " + o.map);
}

CommandRegistration registerShowMapCommand(CLI::App& parent) {
  auto options = std::make_shared<ShowMapOptions>();
  CLI::App* sub = parent.add_subcommand(
      "show-map", "Show a reference map: every reference, its corners, 3D points, cameras");
  sub->footer(
      "Top: the reference images (0 | 1 | ..., numbered), grey dots = corners, coloured dots =\n"
      "corners of map points (colour = depth in the point's first reference, blue near, red\n"
      "far; two references: matches as lines). Bottom: the 3D points and every reference camera\n"
      "(frustum with its index) from a viewpoint behind and above them. Reads map versions 1\n"
      "and 2. Window: Esc or Q closes it.");
  sub->add_option("--map", options->map, "reference map folder (from `reftrack prepare`)")
      ->required()
      ->check(CLI::ExistingDirectory);
  sub->add_flag("--headless", options->headless, "no window (needs --screenshot)");
  CLI::Option* shot =
      sub->add_option("--screenshot", options->screenshot, "write the picture to this PNG file");
  sub->callback([options, shot] {
    if (options->headless && shot->count() == 0)
      throw CLI::RequiredError("--screenshot (with --headless)");
  });
  return {sub, [options] { runShowMap(*options); }};
}

const CommandRegistrar registrar(35, registerShowMapCommand);

}  // namespace

}  // namespace reftrack::app
