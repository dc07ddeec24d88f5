#pragma once
// A head-less OpenGL context for MuJoCo's renderer: OSMesa (default) or EGL
// (Mesa surfaceless). The GL library is dlopen'ed with RTLD_GLOBAL at run
// time instead of linked, because MuJoCo resolves GL through whichever
// *GetProcAddress it finds first and linking both breaks OSMesa. One process
// can therefore use one backend only.
#include <memory>
#include <string>

namespace depot::sim {

enum class GlBackend { kOsMesa, kEgl };

GlBackend parse_gl_backend(const std::string& name);  // "osmesa" | "egl"
const char* gl_backend_name(GlBackend b);

class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual void make_current() = 0;
  GlBackend backend() const { return backend_; }

  // Creates and makes current a context; throws depot::Error on failure or
  // when another backend was already used in this process.
  static std::unique_ptr<GlContext> create(GlBackend backend, int width, int height);

 protected:
  GlBackend backend_ = GlBackend::kOsMesa;
};

}  // namespace depot::sim
