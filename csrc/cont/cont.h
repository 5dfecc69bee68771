#ifndef WASHER_CONT_H
#define WASHER_CONT_H
#include <stddef.h>
#include <stdint.h>
#ifdef __cplusplus
extern "C" {
#endif
#include "cont_api.h"
#ifdef __cplusplus
}

#include <cstddef>
#include <memory>

// A work array whose elements start undefined (std::vector's resize writes zeros into
// every element first): for arrays each call writes in full before reading them.
template <class T> class RawBuffer {
  public:
    RawBuffer() = default;
    explicit RawBuffer(size_t n) { allocate(n); }
    // n undefined elements (the old ones are dropped)
    void allocate(size_t n) {
        if (n != n_) p_.reset(n ? new T[n] : nullptr);
        n_ = n;
    }
    size_t size() const { return n_; }
    T *data() { return p_.get(); }
    const T *data() const { return p_.get(); }
    T *begin() { return p_.get(); }
    T *end() { return p_.get() + n_; }
    const T *begin() const { return p_.get(); }
    const T *end() const { return p_.get() + n_; }
    T &operator[](size_t i) { return p_[i]; }
    const T &operator[](size_t i) const { return p_[i]; }

  private:
    std::unique_ptr<T[]> p_;
    size_t n_ = 0;
};
#endif
#endif
