#include "core/memory_budget.h"

#include <atomic>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <mutex>

#include "core/error.h"
#include "core/usable_memory.h"

namespace iris {

namespace {

constexpr const char* kLimitEnv = "IRIS_MEMORY_LIMIT";

std::atomic<uint64_t> gCharged{0};
std::atomic<uint64_t> gLimit{0};
std::atomic<bool> gLimitIsDefault{false};
std::once_flag gLimitFromEnv;
thread_local MemoryAccount* tCurrent = nullptr;

/// IRIS_MEMORY_LIMIT if set, else the default.
void readLimitFromEnvironment() {
    std::call_once(gLimitFromEnv, [] {
        const char* v = std::getenv(kLimitEnv);
        if (v && *v) {
            gLimit = withLocation({}, [&] { return parseByteSize(v); }, strCat(kLimitEnv, ": "));
        } else {
            gLimit = defaultMemoryLimit();
            gLimitIsDefault = true;
        }
    });
}

/// Where the limit came from, for the refusal's message.
std::string limitOrigin() {
    if (!gLimitIsDefault) return strCat("the limit is set by --memory-limit or ", kLimitEnv);
    const UsableMemory m = usableMemory();
    return strCat("the default limit is ", kDefaultLimitPercent, " % of the ", formatBytes(m.bytes), " of ", m.source,
                  "; set another with --memory-limit or ", kLimitEnv, ", 0 for none");
}

}  // namespace

uint64_t memoryLimit() {
    readLimitFromEnvironment();
    return gLimit;
}

void setMemoryLimit(uint64_t bytes) {
    readLimitFromEnvironment();  // so that a later first charge does not overwrite this
    gLimit = bytes;
    gLimitIsDefault = false;
}

uint64_t defaultMemoryLimit() { return usableMemory().bytes / 100 * kDefaultLimitPercent; }

uint64_t memoryCharged() { return gCharged; }

uint64_t parseByteSize(std::string_view text) {
    auto bad = [&] { fail("invalid memory size '", text, "' (expected a number with an optional unit K, M, G or T, e.g. 512M or 4G)"); };
    size_t i = 0;
    while (i < text.size() && (std::isdigit((unsigned char)text[i]) || text[i] == '.')) ++i;
    double value = 0;
    const auto [p, ec] = std::from_chars(text.data(), text.data() + i, value);
    if (i == 0 || ec != std::errc() || p != text.data() + i) bad();
    std::string unit(text.substr(i));
    for (char& c : unit) c = char(std::toupper((unsigned char)c));
    if (unit.size() > 1 && unit.back() == 'B') unit.pop_back();            // "GB", "GIB"
    if (unit.size() == 2 && unit.back() == 'I') unit.pop_back();           // "GI"
    int power = 0;
    if (unit == "K") power = 1;
    else if (unit == "M") power = 2;
    else if (unit == "G") power = 3;
    else if (unit == "T") power = 4;
    else if (!unit.empty() && unit != "B") bad();
    const double bytes = value * std::pow(1024.0, power);
    if (!(bytes < 0x1p63)) bad();
    return uint64_t(bytes);
}

std::string formatBytes(uint64_t bytes) {
    const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
    double v = double(bytes);
    int u = 0;
    while (v >= 1024 && u < 4) v /= 1024, ++u;
    char buf[32];
    std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", v, units[u]);
    return buf;
}

namespace {

/// Add `bytes` to what is in use if `hold`, after checking the limit.
void charge(uint64_t bytes, std::string_view what, bool hold) {
    const uint64_t limit = memoryLimit();
    uint64_t before = gCharged.load();
    for (;;) {
        const uint64_t after = before + bytes;
        if (limit > 0 && (after < before || after > limit))
            fail(what, " needs ", formatBytes(bytes), ", over the memory limit of ", formatBytes(limit), " (",
                 formatBytes(before), " already in use; ", limitOrigin(), ")");
        if (!hold) return;
        if (gCharged.compare_exchange_weak(before, after)) break;
    }
}

}  // namespace

void chargeMemory(uint64_t bytes, std::string_view what) {
    charge(bytes, what, tCurrent != nullptr);  // no account: checked, not held (an image read by `compare`)
    if (tCurrent) tCurrent->bytes_ += bytes;
}

void checkMemory(uint64_t bytes, std::string_view what) { charge(bytes, what, false); }

MemoryReservation::~MemoryReservation() { gCharged -= bytes_; }

MemoryAccount::MemoryAccount() : outer_(tCurrent) { tCurrent = this; }

MemoryAccount::~MemoryAccount() {
    tCurrent = outer_;
    gCharged -= bytes_;
}

std::shared_ptr<const MemoryReservation> MemoryAccount::take() {
    auto r = std::make_shared<const MemoryReservation>(bytes_);
    bytes_ = 0;
    return r;
}

}  // namespace iris
