// An allocator for large arrays that their makers fill whole in parallel: the values a
// container makes without arguments (std::vector's resize) are left as the memory has them.
// Zeroing first would be a serial pass over tens of megabytes at production sizes, mostly the
// kernel's page faults, while the threads that fill the array touch its memory anyway. Values
// made from arguments (a fill value, a copy) are made as std::allocator makes them. Only for
// types whose every byte the filling writes before anything reads it.
#pragma once

#include <memory>
#include <utility>

namespace steadylight {

template <class T>
struct UnfilledAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = UnfilledAllocator<U>;
    };
    UnfilledAllocator() = default;
    template <class U>
    UnfilledAllocator(const UnfilledAllocator<U>&) noexcept {}
    template <class U>
    void construct(U*) noexcept {}
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

}  // namespace steadylight
