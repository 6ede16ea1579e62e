/* A stand-in libOSMesa.so.8 for a GPU machine (bench/gpu_kit.sh): the
 * voxlab binary links OSMesa, whose real library pulls in LLVM (about
 * 100 MB), while on such a machine everything renders through EGL
 * (VOXLAB_GL=egl). Each entry point voxlab uses exists and fails, so that
 * the binary loads and an accidental OSMesa context says so. */
#include <stddef.h>

typedef void* OSMesaContext;
typedef void (*OSMESAproc)(void);

OSMesaContext OSMesaCreateContextAttribs(const int* attribs, OSMesaContext share) {
    (void)attribs;
    (void)share;
    return NULL;
}
unsigned char OSMesaMakeCurrent(OSMesaContext c, void* buffer, unsigned type, int width, int height) {
    (void)c, (void)buffer, (void)type, (void)width, (void)height;
    return 0;
}
OSMESAproc OSMesaGetProcAddress(const char* name) {
    (void)name;
    return NULL;
}
void OSMesaDestroyContext(OSMesaContext c) { (void)c; }
