// fluid::gl internals — the one place that includes the GL headers. Desktop OpenGL 3.3 core
// through GLEW (first, as it must come before any other GL header); with FLUID_GL_ES, OpenGL
// ES 3.0 (WebGL2 in a browser, emscripten's headers; Mesa's GLESv2 natively), whose entry
// points are linked directly. Public headers never include this.
#pragma once
#if defined(FLUID_GL_ES)
#include <GLES3/gl3.h>
#else
#include <GL/glew.h>
#endif
