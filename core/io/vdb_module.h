/* The C interface of the OpenVDB module (libiris_vdb.so, core/io/vdb_module.cpp).
 *
 * OpenVDB and the libraries it needs (boost iostreams, blosc, log4cplus, snappy, ...) made the
 * dynamic loader's relocations most of the start-up time of every executable that linked it, with
 * or without a .vdb file. The renderer therefore links it only into this small module, which
 * core/io/vdb_loader.cpp loads with dlopen the first time a .vdb grid is read
 * (core/io/vdb_reader.cpp).
 *
 * Reading is split in two so that the caller can charge the memory budget before the dense floats
 * exist: iris_vdb_open reads the grid and reports its dense shape, the caller charges and
 * allocates, iris_vdb_read_dense fills. Plain C types only, so that nothing C++ (exceptions,
 * std::string, OpenVDB types) crosses the boundary. Every function that can fail returns 0 (NULL)
 * on failure and writes a NUL-terminated message, without the file name, into err[errlen] (the
 * caller prefixes "path: "). Bump IRIS_VDB_ABI_VERSION on any change below. */
#ifndef IRIS_CORE_IO_VDB_MODULE_H
#define IRIS_CORE_IO_VDB_MODULE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define IRIS_VDB_ABI_VERSION 1

/* What iris_vdb_open reports about the grid (core/io/vdb_reader.h gives the rules). */
typedef struct iris_vdb_info {
    int dims[3];            /* voxels of the active box along x, y, z (OpenVDB's Coord::dim) */
    int channels;           /* 1 (float, double grids) or 3 (vec3s, vec3d grids) */
    float bbox_min[3];      /* world box of the index box [min - 1/2, max + 1/2] */
    float bbox_max[3];
    const char* grid_name;  /* the grid read (valid until iris_vdb_close) */
} iris_vdb_info;

/* The module's IRIS_VDB_ABI_VERSION (the loader refuses a module of another version). */
typedef int (*iris_vdb_abi_version_fn)(void);

/* Read the grid named grid_name ("" or NULL: the file's only grid) of the .vdb at path, refusing
 * unsupported value types and a grid without active voxels; returns a handle (NULL on failure) and
 * fills *info. The caller has checked the file's size. */
typedef void* (*iris_vdb_open_fn)(const char* path, const char* grid_name, iris_vdb_info* info, char* err,
                                  size_t errlen);

/* Write every voxel of the active box (inactive ones as the background) into out[count], value
 * (x, y, z, c) at ((z*dims[1] + y)*dims[0] + x)*channels + c, as a Mitsuba .vol holds it; count
 * must be the product of dims and channels. Fails on the first non-finite value (or one beyond
 * float's range), naming it and its voxel. */
typedef int (*iris_vdb_read_dense_fn)(void* handle, float* out, size_t count, char* err, size_t errlen);

/* Free a grid opened by iris_vdb_open (NULL is ignored). */
typedef void (*iris_vdb_close_fn)(void* handle);

#ifdef __cplusplus
}
#endif

#endif
