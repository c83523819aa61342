#pragma once
// An owning pointer to a polymorphic object that copies by cloning it, so a class holding
// bodies or forces (the World) copies with `= default` instead of listing its members by hand.
#include <memory>
#include <utility>

namespace pba {

/// Owns a T (or a class derived from it); copying calls T::clone(), which returns a
/// std::unique_ptr<T> to a deep copy.
template <class T>
class ClonePtr {
public:
    ClonePtr() = default;
    ClonePtr(std::unique_ptr<T> owned) noexcept : m_owned(std::move(owned)) {} // NOLINT: implicit by design
    ClonePtr(const ClonePtr& other) : m_owned(other.m_owned ? other.m_owned->clone() : nullptr) {}
    ClonePtr(ClonePtr&&) noexcept = default;
    ClonePtr& operator=(const ClonePtr& other)
    {
        if (this != &other)
            m_owned = other.m_owned ? other.m_owned->clone() : nullptr;
        return *this;
    }
    ClonePtr& operator=(ClonePtr&&) noexcept = default;
    ~ClonePtr() = default;

    T& operator*() const { return *m_owned; }
    T* operator->() const { return m_owned.get(); }
    T* get() const { return m_owned.get(); }
    explicit operator bool() const { return m_owned != nullptr; }

private:
    std::unique_ptr<T> m_owned;
};

} // namespace pba
