// Owners whose copies behave as a snapshot needs: a copy of the World is a complete, independent
// state that steps on to the same bits, and each part it owns through a pointer says what a copy
// does with it. ClonePtr deep-copies state a tick's result depends on; CachePtr and KeptPtr hold
// parts that carry no such state (a factorisation, an index, a worker thread). Internal to the
// engine: not installed.
#pragma once

#include <memory>
#include <utility>

namespace fixstep::detail {

/// Deep-copying owner of a T defined elsewhere (its copy, assignment and deletion are
/// instantiated where T is complete): a copy of the World copies the disc contacts' state,
/// warm-start impulses included, so a snapshot steps on to the same bits.
template <class T>
class ClonePtr {
 public:
  ClonePtr() = default;
  ClonePtr(const ClonePtr& other) : p_(other.p_ ? clone(*other.p_) : nullptr) {}
  ClonePtr& operator=(const ClonePtr& other) {
    if (this != &other) assign(p_, other.p_);
    return *this;
  }
  ClonePtr(ClonePtr&& other) noexcept : p_(other.p_) { other.p_ = nullptr; }
  ClonePtr& operator=(ClonePtr&& other) noexcept {
    std::swap(p_, other.p_);
    return *this;
  }
  ~ClonePtr() { destroy(p_); }
  [[nodiscard]] T* get() const { return p_; }
  T* operator->() const { return p_; }
  T& operator*() const { return *p_; }
  explicit operator bool() const { return p_ != nullptr; }
  void reset(T* p = nullptr) {
    destroy(p_);
    p_ = p;
  }

 private:
  static T* clone(const T& t);
  static void assign(T*& to, const T* from);  ///< reuses *to's storage when both exist
  static void destroy(T* t);
  T* p_ = nullptr;
};

/// Owns a cache that a copy of its owner does not share: a copy starts empty (the owner
/// rebuilds the cache on demand) and copying into an owner drops its cache; moving moves it.
/// For parts that hold no state a tick's result depends on: the implicit solver's
/// factorisation and the name index, so a World can be copied (a snapshot) and stays bit-exact.
template <class T, class Deleter>
class CachePtr : public std::unique_ptr<T, Deleter> {
 public:
  CachePtr() = default;
  CachePtr(const CachePtr& /*other*/) noexcept : std::unique_ptr<T, Deleter>() {}
  CachePtr& operator=(const CachePtr& other) noexcept {
    if (this != &other) this->reset();
    return *this;
  }
  CachePtr(CachePtr&&) noexcept = default;
  CachePtr& operator=(CachePtr&&) noexcept = default;
  ~CachePtr() = default;
};

/// Owns a worker (Workers) that a copy of its owner does not share: a copy starts without one
/// (its first parallel pass starts it), and copying into an owner keeps the owner's own, since
/// a thread holds no state a tick's result depends on and a rollback restores every frame;
/// moving moves it.
template <class T, class Deleter>
class KeptPtr : public std::unique_ptr<T, Deleter> {
 public:
  KeptPtr() = default;
  KeptPtr(const KeptPtr& /*other*/) noexcept : std::unique_ptr<T, Deleter>() {}
  KeptPtr& operator=(const KeptPtr& /*other*/) noexcept { return *this; }
  KeptPtr(KeptPtr&&) noexcept = default;
  KeptPtr& operator=(KeptPtr&&) noexcept = default;
  ~KeptPtr() = default;
};

}  // namespace fixstep::detail
