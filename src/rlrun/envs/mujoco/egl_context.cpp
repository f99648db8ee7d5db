#include "rlrun/envs/mujoco/egl_context.hpp"

#include <array>
#include <cstdint>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/mujoco/gl_library.hpp"

namespace rlrun::mujoco {

namespace {

// The part of Khronos' EGL/egl.h and EGL/eglext.h used here, declared so that building rlrun
// needs no GL headers.
using EGLDisplay = void*;
using EGLConfig = void*;
using EGLContext = void*;
using EGLSurface = void*;
using EGLDeviceEXT = void*;
using EGLint = int32_t;
using EGLBoolean = unsigned;
using EGLenum = unsigned;
using GetProcAddress = void* (*)(const char*);
using QueryDevices = EGLBoolean (*)(EGLint max_devices, EGLDeviceEXT* devices, EGLint* count);
using GetPlatformDisplay = EGLDisplay (*)(EGLenum platform, void* native, const EGLint* attribs);
using Initialize = EGLBoolean (*)(EGLDisplay, EGLint* major, EGLint* minor);
using ChooseConfig = EGLBoolean (*)(EGLDisplay, const EGLint* attribs, EGLConfig* configs,
                                    EGLint size, EGLint* count);
using BindApi = EGLBoolean (*)(EGLenum api);
using CreateContext = EGLContext (*)(EGLDisplay, EGLConfig, EGLContext share, const EGLint*);
using MakeCurrent = EGLBoolean (*)(EGLDisplay, EGLSurface draw, EGLSurface read, EGLContext);
using DestroyContext = EGLBoolean (*)(EGLDisplay, EGLContext);
constexpr EGLenum kPlatformDevice = 0x313F;  // EGL_PLATFORM_DEVICE_EXT
constexpr EGLenum kOpenGlApi = 0x30A2;       // EGL_OPENGL_API
constexpr const char* kLibrary = "libEGL";

// The configuration MuJoCo's Python bindings ask for (python/mujoco/egl, EGL_ATTRIBUTES): RGBA8,
// depth 24, stencil 8, pbuffer-capable, desktop OpenGL. (EGL_SURFACE_TYPE defaults to windows,
// which a device display has none of.)
constexpr std::array<EGLint, 19> kConfigAttributes = {
    0x3024, 8,       // EGL_RED_SIZE
    0x3023, 8,       // EGL_GREEN_SIZE
    0x3022, 8,       // EGL_BLUE_SIZE
    0x3021, 8,       // EGL_ALPHA_SIZE
    0x3025, 24,      // EGL_DEPTH_SIZE
    0x3026, 8,       // EGL_STENCIL_SIZE
    0x303F, 0x308E,  // EGL_COLOR_BUFFER_TYPE, EGL_RGB_BUFFER
    0x3033, 0x0001,  // EGL_SURFACE_TYPE, EGL_PBUFFER_BIT
    0x3040, 0x0008,  // EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT
    0x3038};         // EGL_NONE

struct EglApi {
  BindApi bind_api = nullptr;
  CreateContext create = nullptr;
  MakeCurrent make_current = nullptr;
  DestroyContext destroy = nullptr;
  EGLDisplay display = nullptr;  // initialized once, kept for the life of the process
  EGLConfig config = nullptr;
  std::string error;  // why EGL cannot be used; "" when it can
};

// The first device whose display initializes and offers kConfigAttributes (MuJoCo's bindings
// try the devices in the same order).
void open_device_display(void* library, EglApi& api) {
  const auto get_proc = gl_function<GetProcAddress>(library, kLibrary, "eglGetProcAddress");
  const auto query_devices = reinterpret_cast<QueryDevices>(get_proc("eglQueryDevicesEXT"));
  const auto platform_display =
      reinterpret_cast<GetPlatformDisplay>(get_proc("eglGetPlatformDisplayEXT"));
  if (!query_devices || !platform_display) {
    api.error = "this EGL has no EGL_EXT_platform_device (eglQueryDevicesEXT)";
    return;
  }
  const auto initialize = gl_function<Initialize>(library, kLibrary, "eglInitialize");
  const auto choose_config = gl_function<ChooseConfig>(library, kLibrary, "eglChooseConfig");
  std::array<EGLDeviceEXT, 16> devices{};
  EGLint count = 0;
  if (!query_devices(static_cast<EGLint>(devices.size()), devices.data(), &count) || count < 1) {
    api.error = "EGL finds no device";
    return;
  }
  for (EGLint i = 0; i < count; ++i) {
    EGLDisplay display =
        platform_display(kPlatformDevice, devices[static_cast<size_t>(i)], nullptr);
    EGLint major = 0, minor = 0, configs = 0;
    if (!display || !initialize(display, &major, &minor)) continue;
    if (choose_config(display, kConfigAttributes.data(), &api.config, 1, &configs) &&
        configs >= 1) {
      api.display = display;
      return;
    }
  }
  api.error = "no EGL device offers an OpenGL configuration (RGBA8, depth 24, stencil 8)";
}

EglApi load_egl_api() {
  EglApi api;
  void* library = open_gl_library({"libEGL.so.1", "libEGL.so"}, api.error);
  if (!library) return api;
  try {
    api.bind_api = gl_function<BindApi>(library, kLibrary, "eglBindAPI");
    api.create = gl_function<CreateContext>(library, kLibrary, "eglCreateContext");
    api.make_current = gl_function<MakeCurrent>(library, kLibrary, "eglMakeCurrent");
    api.destroy = gl_function<DestroyContext>(library, kLibrary, "eglDestroyContext");
    open_device_display(library, api);
  } catch (const RuntimeFailure& e) {
    api.error = e.what();
  }
  return api;
}

const EglApi& egl_api() {
  static const EglApi api = load_egl_api();
  return api;
}

class EglContext : public OffscreenGlContext {
 public:
  EglContext() : api_(egl_api()) {
    // The rendering API is per thread (EGL 1.5, 3.7): desktop OpenGL, not the default GLES.
    api_.bind_api(kOpenGlApi);
    context_ = api_.create(api_.display, api_.config, nullptr, nullptr);
    if (!context_) throw RuntimeFailure("EGL could not create an OpenGL context");
  }
  ~EglContext() override { api_.destroy(api_.display, context_); }
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  void make_current() override {
    api_.bind_api(kOpenGlApi);
    if (!api_.make_current(api_.display, nullptr, nullptr, context_))
      throw RuntimeFailure("EGL could not make its OpenGL context current");
  }
  // Releasing acts on the thread's current API's context, hence eglBindAPI first.
  void release() noexcept override {
    api_.bind_api(kOpenGlApi);
    api_.make_current(api_.display, nullptr, nullptr, nullptr);
  }
  const char* platform() const override { return "egl"; }

 private:
  const EglApi& api_;
  EGLContext context_ = nullptr;
};

}  // namespace

bool load_egl(std::string& why_not) {
  const EglApi& api = egl_api();
  why_not = api.error;
  return api.display != nullptr;
}

std::unique_ptr<OffscreenGlContext> make_egl_context() { return std::make_unique<EglContext>(); }

}  // namespace rlrun::mujoco
