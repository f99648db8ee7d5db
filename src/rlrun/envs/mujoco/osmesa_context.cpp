#include "rlrun/envs/mujoco/osmesa_context.hpp"

#include <array>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/mujoco/gl_library.hpp"

namespace rlrun::mujoco {

namespace {

// The part of Mesa's GL/osmesa.h used here, declared so that building rlrun needs no GL headers.
using OSMesaContext = struct osmesa_context*;
using CreateContextExt = OSMesaContext (*)(unsigned format, int depth_bits, int stencil_bits,
                                           int accum_bits, OSMesaContext share);
using DestroyContext = void (*)(OSMesaContext);
using MakeCurrent = unsigned char (*)(OSMesaContext, void* buffer, unsigned type, int width,
                                      int height);
constexpr unsigned kOsmesaRgba = 0x1908;      // OSMESA_RGBA = GL_RGBA
constexpr unsigned kGlUnsignedByte = 0x1401;  // GL_UNSIGNED_BYTE
constexpr const char* kLibrary = "libOSMesa";

struct OsmesaApi {
  CreateContextExt create = nullptr;
  DestroyContext destroy = nullptr;
  MakeCurrent make_current = nullptr;
  std::string error;  // why it could not be loaded; "" when loaded
};

const OsmesaApi& osmesa_api() {
  static const OsmesaApi api = [] {
    OsmesaApi a;
    // libOSMesa.so.8 is Mesa's soname since 20.x (Debian 11 and 12); .6 the older one; the
    // unversioned name comes with the -dev package only.
    void* library = open_gl_library({"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}, a.error);
    if (!library) return a;
    try {
      a.create = gl_function<CreateContextExt>(library, kLibrary, "OSMesaCreateContextExt");
      a.destroy = gl_function<DestroyContext>(library, kLibrary, "OSMesaDestroyContext");
      a.make_current = gl_function<MakeCurrent>(library, kLibrary, "OSMesaMakeCurrent");
    } catch (const RuntimeFailure& e) {
      a.error = e.what();
      a.create = nullptr;
    }
    return a;
  }();
  return api;
}

class OsmesaContext : public OffscreenGlContext {
 public:
  OsmesaContext() : api_(osmesa_api()) {
    // Depth and stencil as MuJoCo's Python bindings ask (mujoco/osmesa); MuJoCo draws into its
    // own framebuffer objects, so the context's own buffer is one pixel.
    context_ = api_.create(kOsmesaRgba, 24, 8, 0, nullptr);
    if (!context_) throw RuntimeFailure("OSMesa could not create an OpenGL context");
  }
  ~OsmesaContext() override { api_.destroy(context_); }
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;

  void make_current() override {
    if (!api_.make_current(context_, buffer_.data(), kGlUnsignedByte, 1, 1))
      throw RuntimeFailure("OSMesa could not make its OpenGL context current");
  }
  // OSMesaMakeCurrent(NULL, NULL, ...) unbinds the thread's context (Mesa's osmesa.c).
  void release() noexcept override { api_.make_current(nullptr, nullptr, 0, 0, 0); }
  const char* platform() const override { return "osmesa"; }

 private:
  const OsmesaApi& api_;
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> buffer_{};
};

}  // namespace

bool load_osmesa(std::string& why_not) {
  const OsmesaApi& api = osmesa_api();
  why_not = api.error;
  return api.create != nullptr;
}

std::unique_ptr<OffscreenGlContext> make_osmesa_context() {
  return std::make_unique<OsmesaContext>();
}

}  // namespace rlrun::mujoco
