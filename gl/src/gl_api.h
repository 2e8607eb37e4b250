// fluid::gl internals — the one place that includes the GL headers (GLEW first, as it must
// come before any other GL header). Public headers never include this.
#pragma once
#include <GL/glew.h>
