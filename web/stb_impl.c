/* voxlab in the browser: stb's PNG reader and writer. Natively they come
 * from Debian's libstb; here the same headers are compiled once. */
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image.h>
#include <stb_image_write.h>
