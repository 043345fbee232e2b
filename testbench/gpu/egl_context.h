// A headless OpenGL ES 3 context through EGL (no window, no display server): Mesa's
// EGL_PLATFORM_SURFACELESS_MESA (llvmpipe on these machines, a GPU's driver where present),
// else the default display. DESIGN.md section 10.
#pragma once

#include <stdexcept>
#include <string>

namespace pst::gpu {

// No EGL display could be opened (no EGL driver, no device): the tests skip on this one only.
// A display without an OpenGL ES 3 config or context is an error (std::runtime_error).
struct EglUnavailable : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class EglContext {
  public:
    EglContext();  // makes the context current on this thread; throws EglUnavailable, runtime_error
    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    const std::string& renderer() const { return renderer_; }  // GL_RENDERER, e.g. "llvmpipe (...)"
    const std::string& version() const { return version_; }    // GL_VERSION
    const std::string& platform() const { return platform_; }  // "surfaceless" or "default"

  private:
    void init();     // after the display: config, context, current
    void release();  // the context and the display, if any
    void* display_ = nullptr;
    void* context_ = nullptr;
    std::string renderer_, version_, platform_;
};

}  // namespace pst::gpu
