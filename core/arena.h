// Per-thread bump allocator for objects that live for one path sample (BSDFs).
// Objects allocated here are never destroyed: they must be trivially destructible
// (no std::vector / shared_ptr members; hold raw pointers to scene-owned data instead).
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace iris {

class Arena {
public:
    explicit Arena(size_t blockSize = 64 * 1024) : blockSize_(blockSize) {}
    Arena(const Arena&) = delete;
    Arena& operator=(const Arena&) = delete;

    template <typename T, typename... Args>
    T* make(Args&&... args) {
        static_assert(std::is_trivially_destructible_v<T>, "arena objects are never destroyed");
        void* mem = allocate(sizeof(T), alignof(T));
        return new (mem) T(std::forward<Args>(args)...);
    }

    /// An array of n default-initialised T, aligned for T (typed storage: no casts at the caller).
    template <typename T>
    T* makeArray(size_t n) {
        static_assert(std::is_trivially_destructible_v<T>, "arena objects are never destroyed");
        T* p = static_cast<T*>(allocate(sizeof(T) * n, alignof(T)));
        for (size_t i = 0; i < n; ++i) new (p + i) T;
        return p;
    }

    void* allocate(size_t size, size_t align) {
        size_t offset = (used_ + align - 1) & ~(align - 1);
        if (current_ >= blocks_.size() || offset + size > blockSizes_[current_]) {
            nextBlock(size + align);
            offset = 0;
        }
        used_ = offset + size;
        return blocks_[current_].get() + offset;
    }

    /// Forget every allocation; memory blocks are kept for reuse.
    void reset() {
        current_ = 0;
        used_ = 0;
    }

private:
    void nextBlock(size_t minSize) {
        if (!blocks_.empty() && used_ != 0) ++current_;
        while (current_ < blocks_.size() && blockSizes_[current_] < minSize) ++current_;
        if (current_ >= blocks_.size()) {
            const size_t size = std::max(blockSize_, minSize);
            blocks_.emplace_back(new (std::align_val_t(64)) std::byte[size]);
            blockSizes_.push_back(size);
            current_ = blocks_.size() - 1;
        }
        used_ = 0;
    }

    struct AlignedDelete {
        void operator()(std::byte* p) const { ::operator delete[](p, std::align_val_t(64)); }
    };
    size_t blockSize_;
    std::vector<std::unique_ptr<std::byte[], AlignedDelete>> blocks_;
    std::vector<size_t> blockSizes_;
    size_t current_ = 0, used_ = 0;
};

}  // namespace iris
