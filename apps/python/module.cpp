// The extension module iris._iris: iris::Error becomes the Python exception iris.Error (a
// ValueError) with the same "file:line: message" text the command-line tools print.
#include "apps/python/bindings.h"

namespace py = pybind11;

PYBIND11_MODULE(_iris, m) {
    m.doc() = "iris spectral renderer: C++ core of the Python package (see docs/python.md)";
    static py::exception<iris::Error> error(m, "Error", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const iris::Error& e) {
            error(e.what());
        }
    });
    m.attr("version") = IRIS_VERSION;
    iris::python::bindImages(m);
    iris::python::bindRender(m);
    iris::python::bindFilm(m);
    iris::python::bindMaterials(m);
    iris::python::bindSpectra(m);
    iris::python::bindThinFilmIndustry(m);
}
