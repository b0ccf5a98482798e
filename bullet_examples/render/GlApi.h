#pragma once
/// @file GlApi.h
/// OpenGL 3.3 core declarations for the renderer. The functions come straight from GLVND's libOpenGL (every
/// core entry point up to 4.5 is exported there and dispatched to the current context, GLX or EGL), so no
/// loader library is needed.

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
