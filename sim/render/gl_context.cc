#include "sim/render/gl_context.h"

#include <dlfcn.h>
#include <link.h>

#include <mutex>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>

#include "common/error.h"

namespace depot::sim {

GlBackend parse_gl_backend(const std::string& name) {
  if (name == "osmesa") return GlBackend::kOsMesa;
  if (name == "egl") return GlBackend::kEgl;
  fail("--gl", "unknown GL backend '" + name + "' (expected osmesa or egl)");
}

const char* gl_backend_name(GlBackend b) {
  return b == GlBackend::kEgl ? "egl" : "osmesa";
}

namespace {

std::mutex g_backend_mutex;
int g_backend_in_use = -1;

void* open_library(const std::vector<const char*>& names) {
  for (const char* n : names)
    if (void* h = dlopen(n, RTLD_NOW | RTLD_GLOBAL)) return h;
  return nullptr;
}

template <typename F>
F symbol(void* lib, const char* name) {
  void* p = dlsym(lib, name);
  if (!p) fail("GL", std::string("missing symbol ") + name);
  return reinterpret_cast<F>(p);
}

class OsMesaContext : public GlContext {
 public:
  OsMesaContext(int width, int height) : width_(width), height_(height) {
    backend_ = GlBackend::kOsMesa;
    lib_ = open_library({"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"});
    if (!lib_) fail("osmesa", "cannot load libOSMesa (install libosmesa6)");
    auto create = symbol<OSMesaContext (*)(GLenum, GLint, GLint, GLint, OSMesaContext)>(
        lib_, "OSMesaCreateContextExt");
    make_current_fn_ = symbol<GLboolean (*)(OSMesaContext, void*, GLenum, GLsizei, GLsizei)>(
        lib_, "OSMesaMakeCurrent");
    destroy_ = symbol<void (*)(OSMesaContext)>(lib_, "OSMesaDestroyContext");
    ctx_ = create(OSMESA_RGBA, 24, 8, 0, nullptr);
    if (!ctx_) fail("osmesa", "OSMesaCreateContextExt failed");
    buffer_.resize(static_cast<size_t>(width_) * height_ * 4);
    make_current();
  }
  ~OsMesaContext() override {
    if (ctx_) destroy_(ctx_);
  }
  void make_current() override {
    if (!make_current_fn_(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_))
      fail("osmesa", "OSMesaMakeCurrent failed");
  }

 private:
  void* lib_ = nullptr;
  OSMesaContext ctx_ = nullptr;
  GLboolean (*make_current_fn_)(OSMesaContext, void*, GLenum, GLsizei, GLsizei) = nullptr;
  void (*destroy_)(OSMesaContext) = nullptr;
  std::vector<unsigned char> buffer_;
  int width_, height_;
};

class EglContext : public GlContext {
 public:
  EglContext() {
    backend_ = GlBackend::kEgl;
    lib_ = open_library({"libEGL.so.1", "libEGL.so"});
    if (!lib_) fail("egl", "cannot load libEGL (install libegl1 and libegl-mesa0)");
    auto get_proc = symbol<void* (*)(const char*)>(lib_, "eglGetProcAddress");
    auto get_platform_display = reinterpret_cast<EGLDisplay (*)(EGLenum, void*, const EGLint*)>(
        get_proc("eglGetPlatformDisplayEXT"));
    auto initialize = symbol<EGLBoolean (*)(EGLDisplay, EGLint*, EGLint*)>(lib_, "eglInitialize");
    auto choose_config =
        symbol<EGLBoolean (*)(EGLDisplay, const EGLint*, EGLConfig*, EGLint, EGLint*)>(
            lib_, "eglChooseConfig");
    auto bind_api = symbol<EGLBoolean (*)(EGLenum)>(lib_, "eglBindAPI");
    auto create_context = symbol<EGLContext (*)(EGLDisplay, EGLConfig, EGLContext, const EGLint*)>(
        lib_, "eglCreateContext");
    make_current_fn_ = symbol<EGLBoolean (*)(EGLDisplay, EGLSurface, EGLSurface, EGLContext)>(
        lib_, "eglMakeCurrent");
    destroy_context_ = symbol<EGLBoolean (*)(EGLDisplay, EGLContext)>(lib_, "eglDestroyContext");
    terminate_ = symbol<EGLBoolean (*)(EGLDisplay)>(lib_, "eglTerminate");
    if (!get_platform_display) fail("egl", "eglGetPlatformDisplayEXT not available");
    display_ = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display_ == EGL_NO_DISPLAY) fail("egl", "no surfaceless EGL display");
    EGLint major = 0, minor = 0;
    if (!initialize(display_, &major, &minor)) fail("egl", "eglInitialize failed");
    const EGLint attribs[] = {EGL_SURFACE_TYPE,
                              EGL_PBUFFER_BIT,
                              EGL_RED_SIZE,
                              8,
                              EGL_GREEN_SIZE,
                              8,
                              EGL_BLUE_SIZE,
                              8,
                              EGL_ALPHA_SIZE,
                              8,
                              EGL_DEPTH_SIZE,
                              24,
                              EGL_RENDERABLE_TYPE,
                              EGL_OPENGL_BIT,
                              EGL_NONE};
    EGLConfig config;
    EGLint count = 0;
    if (!choose_config(display_, attribs, &config, 1, &count) || count < 1)
      fail("egl", "no suitable EGL config");
    if (!bind_api(EGL_OPENGL_API)) fail("egl", "eglBindAPI(EGL_OPENGL_API) failed");
    ctx_ = create_context(display_, config, EGL_NO_CONTEXT, nullptr);
    if (ctx_ == EGL_NO_CONTEXT) fail("egl", "eglCreateContext failed");
    make_current();
#if defined(__SANITIZE_ADDRESS__)
    // Keep every library EGL loaded (Mesa's vendor library, its driver) to
    // the end, so LeakSanitizer can name the frames of what they keep until
    // exit (and tools/sanitizers/lsan.supp suppress them, as OSMesa's).
    dl_iterate_phdr(
        [](dl_phdr_info* info, size_t, void*) {
          if (info->dlpi_name && info->dlpi_name[0])
            dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
          return 0;
        },
        nullptr);
#endif
  }
  ~EglContext() override {
    if (ctx_ != EGL_NO_CONTEXT) {
      make_current_fn_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      destroy_context_(display_, ctx_);
    }
    if (display_ != EGL_NO_DISPLAY) terminate_(display_);
  }
  void make_current() override {
    if (!make_current_fn_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_))
      fail("egl", "eglMakeCurrent failed");
  }

 private:
  void* lib_ = nullptr;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext ctx_ = EGL_NO_CONTEXT;
  EGLBoolean (*make_current_fn_)(EGLDisplay, EGLSurface, EGLSurface, EGLContext) = nullptr;
  EGLBoolean (*destroy_context_)(EGLDisplay, EGLContext) = nullptr;
  EGLBoolean (*terminate_)(EGLDisplay) = nullptr;
};

}  // namespace

std::unique_ptr<GlContext> GlContext::create(GlBackend backend, int width, int height) {
  {
    std::lock_guard<std::mutex> lock(g_backend_mutex);
    if (g_backend_in_use >= 0 && g_backend_in_use != static_cast<int>(backend))
      fail(gl_backend_name(backend), "another GL backend is already in use in this process");
    g_backend_in_use = static_cast<int>(backend);
  }
  if (backend == GlBackend::kEgl) return std::make_unique<EglContext>();
  return std::make_unique<OsMesaContext>(width, height);
}

}  // namespace depot::sim
