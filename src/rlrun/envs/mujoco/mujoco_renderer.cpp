#include "rlrun/envs/mujoco/mujoco_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/mujoco/mujoco_model.hpp"

namespace rlrun::mujoco {

namespace {

constexpr int kMaxGeoms = 1000;  // Gymnasium's max_geom

// np.median(data.geom_xpos[:, axis]): the middle value, or the mean of the two middle ones; NaN
// when any is NaN.
double median_geom_position(const mjModel& model, const mjData& data, int axis) {
  std::vector<double> values(static_cast<size_t>(model.ngeom));
  for (int g = 0; g < model.ngeom; ++g)
    values[static_cast<size_t>(g)] = data.geom_xpos[3 * g + axis];
  if (values.empty()) return 0.0;
  if (std::any_of(values.begin(), values.end(), [](double v) { return std::isnan(v); }))
    return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

// mjr_readPixels' rows run bottom-up; the frame's top-down, 0x00RRGGBB per pixel.
void copy_flipped(const std::vector<unsigned char>& rgb, Frame& frame) {
  const int width = frame.width(), height = frame.height();
  uint32_t* pixels = frame.pixels();
  for (int y = 0; y < height; ++y) {
    const unsigned char* in = rgb.data() + static_cast<size_t>(height - 1 - y) * width * 3;
    uint32_t* out = pixels + static_cast<size_t>(y) * frame.stride_pixels();
    for (int x = 0; x < width; ++x, in += 3)
      out[x] = (uint32_t{in[0]} << 16) | (uint32_t{in[1]} << 8) | uint32_t{in[2]};
  }
  frame.mark_dirty();
}

}  // namespace

mjvCamera initial_camera(const mjModel& model, const mjData& data, const DefaultCamera& config) {
  mjvCamera camera;
  mjv_defaultCamera(&camera);
  // OffScreenViewer._init_camera
  camera.type = mjCAMERA_FREE;
  camera.fixedcamid = -1;
  for (int axis = 0; axis < 3; ++axis)
    camera.lookat[axis] = median_geom_position(model, data, axis);
  camera.distance = model.stat.extent;
  // MujocoRenderer._set_cam_config
  if (config.trackbodyid) camera.trackbodyid = *config.trackbodyid;
  if (config.distance) camera.distance = *config.distance;
  if (config.lookat) std::copy(config.lookat->begin(), config.lookat->end(), camera.lookat);
  if (config.elevation) camera.elevation = *config.elevation;
  if (config.azimuth) camera.azimuth = *config.azimuth;
  // OffScreenViewer.render(camera_id = mj_name2id(model, mjOBJ_CAMERA, "track"))
  const int track = mj_name2id(&model, mjOBJ_CAMERA, "track");
  if (track >= 0) {
    camera.type = mjCAMERA_FIXED;
    camera.fixedcamid = track;
  }
  return camera;
}

MujocoRenderer::Scene::Scene(const mjModel& model, int max_geoms) {
  mjv_defaultScene(&scene);
  mjv_makeScene(&model, &scene, max_geoms);
}

MujocoRenderer::Scene::~Scene() { mjv_freeScene(&scene); }

MujocoRenderer::MujocoRenderer(const mjModel& model, const mjData& data,
                               const DefaultCamera& camera)
    : gl_(make_offscreen_gl_context()),
      scene_(model, kMaxGeoms),
      camera_(initial_camera(model, data, camera)) {
  mjv_defaultOption(&options_);
  mjv_defaultPerturb(&perturb_);
  mjr_defaultContext(&context_);
}

MujocoRenderer::~MujocoRenderer() {
  try {
    CurrentGlContext current(*gl_);
    mjr_freeContext(&context_);
  } catch (const RuntimeFailure&) {
    // The context cannot be made current: its GL objects go with it, next.
  }
}

void MujocoRenderer::make_context(const mjModel& model, int width, int height) {
  std::unique_ptr<mjModel, ModelDeleter> sized(mj_copyModel(nullptr, &model));
  if (!sized) throw RuntimeFailure("MuJoCo could not copy the model for rendering");
  sized->vis.global.offwidth = width;
  sized->vis.global.offheight = height;
  // Frees what an earlier size made, then makes the buffers anew (MuJoCo's mjr_makeContext).
  mjr_makeContext(sized.get(), &context_, mjFONTSCALE_150);
  if (context_.offWidth != width || context_.offHeight != height)
    throw RuntimeFailure("MuJoCo's renderer could not make a " + std::to_string(width) + "x" +
                         std::to_string(height) + " offscreen buffer");
}

void MujocoRenderer::render(const mjModel& model, mjData& data, Frame& frame) {
  const int width = frame.width(), height = frame.height();
  CurrentGlContext current(*gl_);
  if (width != width_ || height != height_) {
    width_ = height_ = 0;  // until made: a failure leaves it to be made again
    make_context(model, width, height);
    width_ = width;
    height_ = height;
  }
  mjr_setBuffer(mjFB_OFFSCREEN, &context_);
  mjv_updateScene(&model, &data, &options_, &perturb_, &camera_, mjCAT_ALL, &scene_.scene);
  const mjrRect viewport{0, 0, width, height};
  mjr_render(viewport, &scene_.scene, &context_);
  rgb_.resize(static_cast<size_t>(width) * height * 3);
  mjr_readPixels(rgb_.data(), nullptr, viewport, &context_);
  copy_flipped(rgb_, frame);
}

}  // namespace rlrun::mujoco
