// Rendering the MuJoCo tasks (Gymnasium's MujocoRenderer in rgb_array mode, on MuJoCo's own
// renderer and an offscreen OpenGL context): what the frames show, Gymnasium's camera rules,
// several envs and threads, `rlrun record` without a display on either GL platform, and that
// nothing links OpenGL before the first frame.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <numbers>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "rlrun/envs/mujoco/half_cheetah.hpp"
#include "rlrun/envs/mujoco/mujoco_model.hpp"
#include "rlrun/envs/mujoco/mujoco_renderer.hpp"
#include "rlrun/frame.hpp"
#include "runtime/cli_runner.hpp"
#include "runtime/video_probe.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using rlrun::mujoco::HalfCheetah;

namespace {

// Where the cheetah's warm colours are (its torso is tan, its legs rosy; MuJoCo's grey sky and
// green-grey or black floor tiles are not warm).
struct Box {
  int left = 1 << 30, top = 1 << 30, right = -1, bottom = -1, pixels = 0;
  int width() const { return right - left + 1; }
  int height() const { return bottom - top + 1; }
  double centre_y() const { return (top + bottom) / 2.0; }
};

bool warm(Rgb c) { return c.r > c.b + 30 && c.r > c.g + 10; }

std::vector<uint8_t> rgb_of(const Frame& frame) {
  std::vector<uint8_t> rgb;
  frame.to_rgb(rgb);
  return rgb;
}

Box warm_box(const Frame& frame) {
  const std::vector<uint8_t> rgb = rgb_of(frame);
  Box box;
  for (int y = 0; y < frame.height(); ++y)
    for (int x = 0; x < frame.width(); ++x) {
      const uint8_t* p = &rgb[(static_cast<size_t>(y) * frame.width() + x) * 3];
      if (!warm({p[0], p[1], p[2]})) continue;
      box.left = std::min(box.left, x);
      box.right = std::max(box.right, x);
      box.top = std::min(box.top, y);
      box.bottom = std::max(box.bottom, y);
      ++box.pixels;
    }
  return box;
}

// init_qpos with the root's x, z and pitch (rooty) replaced; at rest.
void pose(HalfCheetah& env, double rootx, double rootz, double rooty) {
  std::vector<double> qpos(env.init_qpos().begin(), env.init_qpos().end());
  std::vector<double> qvel(env.init_qvel().begin(), env.init_qvel().end());
  qpos[0] = rootx;
  qpos[1] = rootz;
  qpos[2] = rooty;
  env.set_state(qpos, qvel);
}

// Small frames keep software rendering quick.
std::vector<uint8_t> render_rgb(const Env& env, int width = 120, int height = 90) {
  Frame frame(width, height);
  REQUIRE(env.render(frame));
  return rgb_of(frame);
}

}  // namespace

TEST_CASE("MuJoCo rendering: HalfCheetah's frame shows the cheetah upright", "[mujoco]") {
  HalfCheetah env;
  const RenderSpec spec = env.render_spec();
  CHECK(spec.width == 480);  // Gymnasium's DEFAULT_SIZE
  CHECK(spec.height == 480);
  CHECK(spec.fps == 20.0);  // half_cheetah_v4.py metadata["render_fps"]: round(1 / 0.05)
  std::vector<float> obs(17);
  env.reset(0, obs);
  Frame frame(spec.width, spec.height);
  REQUIRE(env.render(frame));
  // The sky at the top (grey: MuJoCo's skybox), the cheetah in the lower half (the frame is not
  // upside down), longer than tall (legs included).
  const Rgb sky = frame.pixel(240, 5);
  CHECK(std::abs(sky.r - sky.g) < 8);
  CHECK(std::abs(sky.g - sky.b) < 8);
  CHECK(sky.r > 100);
  const Box cheetah = warm_box(frame);
  INFO("cheetah at x " << cheetah.left << ".." << cheetah.right << ", y " << cheetah.top << ".."
                       << cheetah.bottom << ", " << cheetah.pixels << " pixels");
  CHECK(cheetah.pixels > 3000);
  CHECK(cheetah.centre_y() > 240);
  CHECK(cheetah.width() > 1.2 * cheetah.height());
  // The tracking camera ("track", trackcom) keeps the cheetah centred.
  CHECK(std::abs((cheetah.left + cheetah.right) / 2.0 - 240) < 40);

  // On its nose: tall, not long. Another state, another picture.
  pose(env, 0.0, 1.0, std::numbers::pi / 2);
  Frame standing(spec.width, spec.height);
  REQUIRE(env.render(standing));
  const Box tall = warm_box(standing);
  INFO("standing at x " << tall.left << ".." << tall.right << ", y " << tall.top << ".."
                        << tall.bottom);
  CHECK(tall.height() > tall.width());
  CHECK(rgb_of(standing) != rgb_of(frame));

  // Any frame size: the buffers follow it.
  Frame small(320, 240);
  REQUIRE(env.render(small));
  CHECK(warm_box(small).height() > warm_box(small).width());
  CHECK(warm_box(small).centre_y() > 60);
}

TEST_CASE("MuJoCo rendering: Gymnasium's camera rules", "[mujoco]") {
  // A model with the camera "track": that fixed camera.
  ReferenceSim cheetah("half_cheetah.xml");
  const mjvCamera track = mujoco::initial_camera(cheetah.model(), cheetah.data(), {});
  CHECK(track.type == mjCAMERA_FIXED);
  CHECK(track.fixedcamid == mj_name2id(&cheetah.model(), mjOBJ_CAMERA, "track"));

  // Without: the free camera, looking at the median of the geoms' positions from the model's
  // extent (OffScreenViewer._init_camera), then the task's DEFAULT_CAMERA_CONFIG.
  TempDir dir("mujoco_camera");
  std::ofstream(dir / "four.xml") << R"(<mujoco><worldbody>
      <geom type="sphere" size="0.4" pos="0 0 0"/><geom type="sphere" size="0.4" pos="1 2 0"/>
      <geom type="sphere" size="0.4" pos="2 4 1"/><geom type="sphere" size="0.4" pos="9 0 3"/>
    </worldbody></mujoco>)";
  const mujoco::ModelPtr model = mujoco::load_model(dir / "four.xml");
  const mujoco::DataPtr data = mujoco::make_data(*model);
  mj_forward(model.get(), data.get());
  const mjvCamera free = mujoco::initial_camera(*model, *data, {});
  CHECK(free.type == mjCAMERA_FREE);
  CHECK(free.fixedcamid == -1);
  CHECK(free.lookat[0] == 1.5);  // np.median([0, 1, 2, 9]): the mean of the middle two
  CHECK(free.lookat[1] == 1.0);
  CHECK(free.lookat[2] == 0.5);
  CHECK(free.distance == model->stat.extent);
  mjvCamera defaults;
  mjv_defaultCamera(&defaults);
  CHECK(free.azimuth == defaults.azimuth);
  CHECK(free.elevation == defaults.elevation);

  const mujoco::DefaultCamera hopper_like{.trackbodyid = 2,
                                          .distance = 3.0,
                                          .lookat = std::array<double, 3>{0.0, 0.0, 1.15},
                                          .elevation = -20.0,
                                          .azimuth = 100.0};
  const mjvCamera configured = mujoco::initial_camera(*model, *data, hopper_like);
  CHECK(configured.type == mjCAMERA_FREE);  // trackbodyid is set, but a free camera stays put
  CHECK(configured.trackbodyid == 2);
  CHECK(configured.distance == 3.0);
  CHECK(configured.lookat[2] == 1.15);
  CHECK(configured.elevation == -20.0);
  CHECK(configured.azimuth == 100.0);

  // And the free camera draws: lit spheres on MuJoCo's black background (no skybox here).
  mujoco::MujocoRenderer renderer(*model, *data, {});
  Frame frame(200, 150);
  renderer.render(*model, *data, frame);
  std::vector<uint8_t> rgb = rgb_of(frame);
  const auto lit = std::count_if(rgb.begin(), rgb.end(), [](uint8_t v) { return v > 60; });
  CHECK(lit > 100);
}

TEST_CASE("MuJoCo rendering: several envs, in turn and on two threads at once", "[mujoco]") {
  HalfCheetah a, b;
  std::vector<float> obs(17);
  a.reset(1, obs);
  b.reset(2, obs);
  pose(b, 3.0, 1.0, std::numbers::pi / 2);
  const std::vector<uint8_t> alone_a = render_rgb(a);
  const std::vector<uint8_t> alone_b = render_rgb(b);
  REQUIRE(alone_a != alone_b);
  // In turn on one thread: each env's context is current only while it draws.
  CHECK(render_rgb(b) == alone_b);
  CHECK(render_rgb(a) == alone_a);
  CHECK(render_rgb(b) == alone_b);
  // At once, each on its own thread (a context is current on one thread at a time).
  std::vector<uint8_t> on_thread_a, on_thread_b;
  std::thread ta([&] {
    for (int i = 0; i < 2; ++i) on_thread_a = render_rgb(a);
  });
  std::thread tb([&] {
    for (int i = 0; i < 2; ++i) on_thread_b = render_rgb(b);
  });
  ta.join();
  tb.join();
  CHECK(on_thread_a == alone_a);
  CHECK(on_thread_b == alone_b);
  // Rendering reads the state only: the episode goes on as without it.
  HalfCheetah unrendered;
  unrendered.reset(1, obs);
  std::vector<float> obs_rendered(17), obs_unrendered(17);
  const std::vector<float> action(6, 0.5f);
  a.step(action, obs_rendered);
  unrendered.step(action, obs_unrendered);
  CHECK(obs_rendered == obs_unrendered);
}

namespace {

// `rlrun record` of a short random HalfCheetah-v4 episode (`steps` steps) into `video`, with
// the environment settings `env_settings` (for env(1)) and no display.
CommandResult record_cheetah(const std::string& env_settings, int steps, const std::string& size,
                             const std::string& video) {
  return run_command("env -u DISPLAY -u MUJOCO_GL " + env_settings + " " +
                     std::string(RLRUN_BINARY) +
                     " record --env HalfCheetah-v4 --policy random --set env.max_episode_steps=" +
                     std::to_string(steps) + " --size " + size + " --output " + video);
}

}  // namespace

TEST_CASE("MuJoCo rendering: rlrun record HalfCheetah-v4 without a display", "[mujoco][cli]") {
  TempDir dir("mujoco_record");
  // MUJOCO_GL unset: OSMesa.
  const auto r = record_cheetah("", 3, "480x480", dir / "cheetah.mp4");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  // One frame for the reset and one per step, at Gymnasium's size and render_fps.
  CHECK(r.output.find("4 frames at 480x480, 20 fps") != std::string::npos);
  CHECK(probe_video(dir / "cheetah.mp4").find("h264,480,480,4") != std::string::npos);
}

TEST_CASE("MuJoCo rendering: MUJOCO_GL and the process's EGL choose the GL platform",
          "[mujoco][cli]") {
  TempDir dir("mujoco_gl_platform");
  // MUJOCO_GL=egl: an EGL device (Mesa's software one here), as Gymnasium's MUJOCO_GL=egl.
  const auto egl = record_cheetah("MUJOCO_GL=egl", 1, "160x120", dir / "egl.mp4");
  INFO(egl.output);
  REQUIRE(egl.exit_code == 0);
  CHECK(probe_video(dir / "egl.mp4").find("h264,160,120,2") != std::string::npos);

  // A process that has EGL among its global symbols already (here preloaded): MuJoCo's GL
  // loader takes EGL's functions before OSMesa's, so rlrun renders with EGL (on an OSMesa
  // context MuJoCo would stop with "gladLoadGL error"), and refuses MUJOCO_GL=osmesa.
  const auto preloaded = record_cheetah("LD_PRELOAD=libEGL.so.1", 1, "160x120", dir / "pre.mp4");
  INFO(preloaded.output);
  REQUIRE(preloaded.exit_code == 0);
  CHECK(probe_video(dir / "pre.mp4").find("h264,160,120,2") != std::string::npos);
  const auto refused =
      record_cheetah("LD_PRELOAD=libEGL.so.1 MUJOCO_GL=osmesa", 1, "160x120", dir / "refused.mp4");
  CHECK(refused.exit_code == 1);
  CHECK(refused.output.find("this process has already loaded EGL") != std::string::npos);
  CHECK(refused.output.find("set MUJOCO_GL=egl") != std::string::npos);

  // EGL without a vendor library (as without libegl-mesa0): the packages to install.
  const auto no_vendor =
      record_cheetah("MUJOCO_GL=egl __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json", 1, "160x120",
                     dir / "no_vendor.mp4");
  CHECK(no_vendor.exit_code == 1);
  CHECK(no_vendor.output.find("MUJOCO_GL=egl, but EGL does not work: EGL finds no device. "
                              "Install Debian's libegl1 and libegl-mesa0") != std::string::npos);

  // A platform rlrun does not offer headless: a runtime failure that says what to set, and no
  // video.
  const auto glfw = record_cheetah("MUJOCO_GL=glfw", 1, "160x120", dir / "glfw.mp4");
  CHECK(glfw.exit_code == 1);
  CHECK(glfw.output.find("MUJOCO_GL=glfw: rlrun renders MuJoCo offscreen with osmesa or egl") !=
        std::string::npos);
  CHECK(!std::filesystem::exists(dir / "glfw.mp4"));
}

TEST_CASE("MuJoCo rendering: rlrun opens OpenGL at the first frame, never at load", "[mujoco]") {
  // The rlrun program links MuJoCo, which finds GL itself at run time; rlrun opens libOSMesa or
  // libEGL only when an env draws, so machines without them train, and the deploy library has
  // neither (test_spaces_without_env.cpp checks it links no simulator at all).
  for (const char* binary : {RLRUN_BINARY, RLRUN_POLICY_LIBRARY}) {
    const auto r = run_command(std::string("ldd ") + binary);
    INFO(r.output);
    REQUIRE(r.exit_code == 0);
    for (const char* gl : {"libOSMesa", "libGL", "libEGL", "libOpenGL", "libglapi"})
      CHECK(r.output.find(gl) == std::string::npos);
  }
}
