// The pieces of the Python module `iris._iris` (docs/python.md): one bind* function per area,
// called from module.cpp, and the NumPy helpers they share. The Python package apps/python/iris
// wraps these functions with keyword arguments, broadcasting and validation of array inputs.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "core/error.h"

namespace iris::python {

namespace py = pybind11;

void bindImages(py::module_& m);    // read / write EXR (image_bindings.cpp)
void bindRender(py::module_& m);    // scenes and rendering (render_bindings.cpp)
void bindFilm(py::module_& m);      // thin-film stack optics (thin_film_bindings.cpp)
void bindMaterials(py::module_& m); // BSDF eval / pdf / sample (material_bindings.cpp)
void bindSpectra(py::module_& m);   // CIE data, XYZ, colour spaces, RGB upsampling (spectra_bindings.cpp)
void bindThinFilmIndustry(py::module_& m);  // the industry's RGB thin films (thin_film_industry_bindings.cpp)

/// A NumPy array that owns `values` (moved to the heap and freed with the array): no copy.
template <typename T>
py::array_t<T> ownedArray(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
    auto* heap = new std::vector<T>(std::move(values));
    py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>(shape, heap->data(), owner);
}

/// C-contiguous input array of dtype T with exactly `ndim` dimensions (last dimension `last` when
/// last >= 0); iris::Error "name: ..." otherwise.
template <typename T>
py::array_t<T, py::array::c_style | py::array::forcecast> inputArray(const py::array& a, const char* name, int ndim,
                                                                     py::ssize_t last = -1) {
    auto r = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!r) fail(name, ": cannot be converted to an array of ", py::format_descriptor<T>::format());
    if (r.ndim() != ndim) fail(name, ": expected ", ndim, " dimensions, got ", r.ndim());
    if (last >= 0 && r.shape(ndim - 1) != last) fail(name, ": expected the last dimension to be ", last, ", got ", r.shape(ndim - 1));
    return r;
}

}  // namespace iris::python
