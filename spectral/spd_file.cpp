// ".spd" files: one "lambda value" pair per line; '#' or ';' start a comment (whole line or
// trailing). Wavelengths are nm; a wavelength below 100 is read as micrometres (× 1000).
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"
#include "spectral/piecewise_linear_spectrum.h"
#include "spectral/spectrum_factory.h"

namespace iris {

SpectrumPtr loadSpdFile(const std::string& path, SpectrumKind kind) {
    // Read whole through the input-file checks: a device (/dev/zero) would grow one line without end.
    std::istringstream in(readInputFile(path, "spectrum file", kMaxSpectrumFileBytes));
    std::vector<float> lambdas, values;
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        const size_t comment = line.find_first_of("#;");
        if (comment != std::string::npos) line.resize(comment);
        std::istringstream ls(line);
        std::string first;
        if (!(ls >> first)) continue;  // blank or comment-only line
        std::istringstream row(line);
        double lambda, value;
        if (!(row >> lambda >> value))
            fail(path, ":", lineNo, ": expected \"wavelength value\", got \"", line, "\"");
        std::string extra;
        if (row >> extra) fail(path, ":", lineNo, ": unexpected extra text \"", extra, "\" after \"wavelength value\"");
        if (!std::isfinite(lambda) || !std::isfinite(value) || lambda <= 0)
            fail(path, ":", lineNo, ": invalid wavelength or value in \"", line, "\"");
        if (lambda < 100.0) lambda *= 1000.0;  // µm → nm
        if (!lambdas.empty() && !(float(lambda) > lambdas.back()))
            fail(path, ":", lineNo, ": wavelengths must be strictly increasing (", lambdas.back(), " nm then ", lambda,
                 " nm)");
        lambdas.push_back(float(lambda));
        values.push_back(float(value));
    }
    if (lambdas.empty()) fail(path, ": no \"wavelength value\" lines in spectrum file");
    return std::make_shared<PiecewiseLinearSpectrum>(std::move(lambdas), std::move(values), kind);
}

}  // namespace iris
