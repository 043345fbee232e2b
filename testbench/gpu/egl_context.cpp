// Headless EGL + OpenGL ES 3 context; see egl_context.h.
#include "egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>

#include <cstdio>

namespace pst::gpu {

namespace {

std::string eglError(const char* step) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "0x%04x", eglGetError());
    return std::string("EGL: ") + step + " failed (error " + buf + ")";
}

}  // namespace

EglContext::EglContext() {
    EGLDisplay d = EGL_NO_DISPLAY;
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (getPlatformDisplay) {
        d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        platform_ = "surfaceless";
        if (d != EGL_NO_DISPLAY && !eglInitialize(d, nullptr, nullptr)) d = EGL_NO_DISPLAY;
    }
    if (d == EGL_NO_DISPLAY) {
        d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        platform_ = "default";
        if (d != EGL_NO_DISPLAY && !eglInitialize(d, nullptr, nullptr)) d = EGL_NO_DISPLAY;
    }
    if (d == EGL_NO_DISPLAY)
        throw EglUnavailable(
            "EGL: no EGL device could be opened (eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA) "
            "and eglGetDisplay(EGL_DEFAULT_DISPLAY) both failed; on Debian install libegl-mesa0 "
            "libgl1-mesa-dri, scripts/setup.sh)");
    display_ = d;
    try {
        init();
    } catch (...) {
        release();
        throw;
    }
}

void EglContext::init() {
    EGLDisplay d = display_;
    if (!eglBindAPI(EGL_OPENGL_ES_API)) throw std::runtime_error(eglError("eglBindAPI(EGL_OPENGL_ES_API)"));
    // EGL_SURFACE_TYPE defaults to EGL_WINDOW_BIT, which no surfaceless config has.
    const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_SURFACE_TYPE, EGL_DONT_CARE, EGL_NONE};
    EGLConfig config;
    EGLint count = 0;
    if (!eglChooseConfig(d, attribs, &config, 1, &count) || count < 1)
        throw std::runtime_error(eglError("eglChooseConfig(EGL_OPENGL_ES3_BIT)"));
    const EGLint ctxAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLContext ctx = eglCreateContext(d, config, EGL_NO_CONTEXT, ctxAttribs);
    if (ctx == EGL_NO_CONTEXT) throw std::runtime_error(eglError("eglCreateContext (OpenGL ES 3)"));
    context_ = ctx;
    if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
        throw std::runtime_error(eglError("eglMakeCurrent without a surface"));
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
}

EglContext::~EglContext() { release(); }

void EglContext::release() {
    if (display_) {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (context_) eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
    display_ = context_ = nullptr;
}

}  // namespace pst::gpu
