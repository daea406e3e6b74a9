// Shards of one split render: film states (Film::save) of disjoint sample ranges of the same scene
// and settings. mergeFilmShards checks that the shards belong together — same settings key (scene
// path and hash, mode, wavelengths, seed, resolution, integrator), each complete for its range, the
// ranges disjoint and together exactly [0, B) — and adds them exactly (Film::add), so the result
// equals the unsplit render bit for bit. Every refusal names the files and what is wrong.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/film.h"

namespace iris {

struct FilmShard {
    std::string path;
    std::string key;          // settings key without its first_sample field
    int64_t begin = 0, end = -1;  // the range the shard was rendered for (end -1: time-limited)
    Film film;
};

/// True if the file starts like a film state (checkpoint) rather than an image.
bool isFilmStateFile(const std::string& path);
/// Read a film state and its sample range. Throws iris::Error naming the file.
FilmShard readFilmShard(const std::string& path);
/// "" if the shard holds every sample of its range, else what is missing.
std::string shardIncompleteness(const FilmShard& s);

struct MergedFilm {
    Film film;
    std::string key;
    int64_t spp = 0;          // the merged range is [0, spp)
};
/// Check and add. `expectedSpp` >= 0 also requires the union to be exactly [0, expectedSpp) (a
/// missing last shard is otherwise invisible). Throws iris::Error listing every problem (missing
/// ranges, overlaps, incomplete shards, mismatched settings).
MergedFilm mergeFilmShards(std::vector<FilmShard> shards, int64_t expectedSpp = -1);

/// The value of field `name` in a settings key "a=1;b=2" ("" if absent).
std::string settingsField(const std::string& key, const std::string& name);

}  // namespace iris
