/* The C interface of the OpenImageIO module (libiris_oiio.so, core/io/oiio_module.cpp).
 *
 * OpenImageIO pulls in about 250 shared libraries (its format plug-ins), whose relocation cost
 * most of the start-up time of every executable that linked it. The renderer therefore links it
 * only into this small module, which core/io/oiio_loader.cpp loads with dlopen the first time a
 * PNG/JPEG is written or a non-EXR image is read (EXR goes through OpenEXR directly).
 *
 * Plain C types only, so that nothing C++ (exceptions, std::string, OIIO types) crosses the
 * boundary. Every function that can fail returns 0 on failure and writes a NUL-terminated message
 * (without the file name) into err[errlen]. Bump IRIS_OIIO_ABI_VERSION on any change below. */
#ifndef IRIS_CORE_IO_OIIO_MODULE_H
#define IRIS_CORE_IO_OIIO_MODULE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define IRIS_OIIO_ABI_VERSION 1

/* What iris_oiio_open reports about an image file (its first subimage, first MIP level). */
typedef struct iris_oiio_info {
    int width, height, depth, channels;
    int integer_format;     /* 1 if the stored pixel type is 8- or 16-bit unsigned integer */
    char color_space[128];  /* the "oiio:ColorSpace" attribute ("" if none), truncated */
} iris_oiio_info;

/* The module's IRIS_OIIO_ABI_VERSION (the loader refuses a module of another version). */
typedef int (*iris_oiio_abi_version_fn)(void);

/* Write 8-bit pixels (width*height*channels bytes, interleaved, top row first) to out_path; the
 * file format is chosen from the extension of format_path (the two differ for atomic writes). */
typedef int (*iris_oiio_write_u8_fn)(const char* format_path, const char* out_path, int width, int height,
                                     int channels, const unsigned char* pixels, char* err, size_t errlen);

/* Open an image for reading; returns a handle (NULL on failure) and fills *info. */
typedef void* (*iris_oiio_open_fn)(const char* path, iris_oiio_info* info, char* err, size_t errlen);

/* Name of channel c of an open image (valid until iris_oiio_close); "" if unnamed. */
typedef const char* (*iris_oiio_channel_name_fn)(void* handle, int c);

/* Read all channels of the open image as float (values as stored: 8-bit code/255, no colour
 * conversion) into out[width*height*channels]. */
typedef int (*iris_oiio_read_float_fn)(void* handle, float* out, char* err, size_t errlen);

/* Close an image opened by iris_oiio_open (NULL is ignored). */
typedef void (*iris_oiio_close_fn)(void* handle);

#ifdef __cplusplus
}
#endif

#endif
