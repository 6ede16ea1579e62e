/* voxlab: OpenGL for the browser build. WebGL 2 is OpenGL ES 3.0, whose
 * functions emscripten links directly, so nothing is loaded at run time. The
 * native build's voxlab_gl.h (framework/gl/, generated) declares the same
 * names for OpenGL 3.3 core; the framework uses only the subset the two
 * share, and the few names ES lacks are mapped here. */
#ifndef VOXLAB_GL_H
#define VOXLAB_GL_H

#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h>

/* 16-bit normalised textures: WebGL 2 has them only with
 * EXT_texture_norm16; scene_volumes.cpp chooses a half-float texture
 * where the extension is absent (see docs/web.md). */
#ifndef GL_R16
#define GL_R16 0x822A
#endif
#ifndef GL_TEXTURE_SWIZZLE_RGBA
#define GL_TEXTURE_SWIZZLE_RGBA 0x8E46
#endif

/* Sampler types GLSL ES 3.00 has not; the strict checks' table names them
 * (gl_strict.cpp). WebGL never reports them, so the values only need to
 * differ from the others (the desktop GL's). */
#ifndef GL_SAMPLER_1D
#define GL_SAMPLER_1D 0x8B5D
#endif
#ifndef GL_SAMPLER_BUFFER
#define GL_SAMPLER_BUFFER 0x8DC2
#endif

static inline void glClearDepth(double depth) { glClearDepthf((float)depth); }

typedef void (*VoxlabGLProc)(void);
typedef VoxlabGLProc (*VoxlabGLGetProc)(const char* name);
/* Nothing to load: emscripten binds every GLES 3 function at link time. */
static inline int voxlabLoadGL(VoxlabGLGetProc getProc) { (void)getProc; return 0; }
static inline const char* voxlabGLMissing(int i) { (void)i; return ""; }

#endif
