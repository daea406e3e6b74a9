#include "render/film_shard.h"

#include <algorithm>
#include <fstream>

#include "core/error.h"
#include "core/input_file.h"

namespace iris {

namespace {
constexpr char kFirstSampleField[] = ";first_sample=";

std::string withoutFirstSample(const std::string& key) {
    const size_t at = key.find(kFirstSampleField);
    if (at == std::string::npos) return key;
    const size_t next = key.find(';', at + 1);
    return key.substr(0, at) + (next == std::string::npos ? std::string() : key.substr(next));
}

int64_t parseIndex(const std::string& path, const std::string& text) {
    try {
        size_t pos;
        const long long v = std::stoll(text, &pos);
        if (pos == text.size() && v >= 0) return v;
    } catch (...) {
    }
    fail(path, ": film state has an invalid sample range field '", text, "'");
}
}  // namespace

std::string settingsField(const std::string& key, const std::string& name) {
    const std::string tag = name + "=";
    size_t at = key.rfind(';' + tag);
    at = at == std::string::npos ? (key.rfind(tag, 0) == 0 ? 0 : std::string::npos) : at + 1;
    if (at == std::string::npos) return "";
    const size_t from = at + tag.size(), to = key.find(';', from);
    return key.substr(from, to == std::string::npos ? std::string::npos : to - from);
}

bool isFilmStateFile(const std::string& path) {
    try {
        checkInputFile(path, "film state");  // a FIFO's open would wait; the image reader then says what is wrong
    } catch (const Error&) {
        return false;
    }
    std::ifstream f(path, std::ios::binary);
    char magic[7] = {};
    f.read(magic, 7);
    return f && std::string(magic, 7) == "IRISCKP";
}

FilmShard readFilmShard(const std::string& path) {
    std::string header;
    Film film = Film::read(path, &header);
    const size_t nl = header.find('\n');
    const std::string key = header.substr(0, nl);
    const std::string range = nl == std::string::npos ? std::string() : header.substr(nl + 1);
    if (range.rfind("samples=", 0) != 0 || range.find(':') == std::string::npos)
        fail(path, ": film state records no sample range (written by an older iris?)");
    const std::string a = range.substr(8, range.find(':') - 8), b = range.substr(range.find(':') + 1);
    FilmShard s{path, withoutFirstSample(key), parseIndex(path, a), b.empty() ? -1 : parseIndex(path, b), std::move(film)};
    if (s.end >= 0 && s.end <= s.begin) fail(path, ": film state has an empty sample range ", a, ":", b);
    return s;
}

std::string shardIncompleteness(const FilmShard& s) {
    if (s.end < 0) return "was rendered with a time limit (no fixed sample range)";
    const int64_t want = s.end - s.begin;
    const uint32_t lo = s.film.minSampleCount();
    if (lo == want && s.film.totalSamples() == uint64_t(want) * uint64_t(s.film.width()) * uint64_t(s.film.height()))
        return "";
    return strCat("holds ", lo, " of its ", want, " samples per pixel (interrupted: resume or re-run it)");
}

MergedFilm mergeFilmShards(std::vector<FilmShard> shards, int64_t expectedSpp) {
    if (shards.empty()) fail("no film states to merge");
    std::vector<std::string> problems;
    const FilmShard& ref = shards.front();
    for (const FilmShard& s : shards) {
        if (s.key != ref.key)
            problems.push_back(strCat(s.path, ": different scene or settings than ", ref.path, "\n    ", s.key, "\n    ", ref.key));
        else if (s.film.width() != ref.film.width() || s.film.height() != ref.film.height())
            problems.push_back(strCat(s.path, ": film size differs from ", ref.path));
        if (const std::string why = shardIncompleteness(s); !why.empty()) problems.push_back(strCat(s.path, ": ", why));
    }
    // Fixed order (by first sample) so that even the double sums of squares do not depend on the
    // order of the command line.
    std::sort(shards.begin(), shards.end(), [](const FilmShard& a, const FilmShard& b) { return a.begin < b.begin; });
    int64_t next = 0;
    for (const FilmShard& s : shards) {
        if (s.end < 0) continue;
        if (s.begin > next) problems.push_back(strCat("samples ", next, ":", s.begin, " are missing (no shard holds them)"));
        if (s.begin < next) problems.push_back(strCat(s.path, ": samples ", s.begin, ":", std::min(next, s.end), " overlap another shard"));
        next = std::max(next, s.end);
    }
    if (expectedSpp >= 0 && next < expectedSpp) problems.push_back(strCat("samples ", next, ":", expectedSpp, " are missing (no shard holds them)"));
    if (expectedSpp >= 0 && next > expectedSpp) problems.push_back(strCat("the shards hold samples up to ", next, ", more than the expected ", expectedSpp));
    if (!problems.empty()) {
        std::string msg = "film states do not form one render:";
        for (const std::string& p : problems) msg += "\n  " + p;
        fail(msg);
    }
    MergedFilm m{Film(ref.film.width(), ref.film.height()), ref.key, next};
    for (const FilmShard& s : shards) m.film.add(s.film);
    return m;
}

}  // namespace iris
