#pragma once
// A growable byte buffer for building NC text. Unlike std::string it can hand out room to
// write into directly (room, then commit), so numbers are formatted where they will stay,
// with no length bookkeeping per character and no zero-filling.
#include <cstddef>
#include <cstring>
#include <memory>
#include <string_view>

namespace twinpost {

class text_buffer {
 public:
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const char* data() const { return data_.get(); }
  std::string_view view() const { return {data_.get(), size_}; }
  operator std::string_view() const { return view(); }
  char back() const { return data_[size_ - 1]; }

  void clear() { size_ = 0; }
  /// Forgets everything from `n` on (n <= size()).
  void truncate(std::size_t n) { size_ = n; }
  void reserve(std::size_t n) {
    if (n > cap_) reallocate(n);
  }

  /// At least `n` writable bytes at the end; write there, then commit() the end.
  char* room(std::size_t n) {
    if (cap_ - size_ < n) grow(n);
    return data_.get() + size_;
  }
  void commit(const char* end) { size_ = static_cast<std::size_t>(end - data_.get()); }

  text_buffer& operator+=(char c) {
    *room(1) = c;
    ++size_;
    return *this;
  }
  text_buffer& operator+=(std::string_view s) {
    if (!s.empty()) std::memcpy(room(s.size()), s.data(), s.size());
    size_ += s.size();
    return *this;
  }
  void append(std::string_view s) { *this += s; }
  /// Inserts `s` at `at` (<= size()), moving what follows.
  void insert(std::size_t at, std::string_view s) {
    room(s.size());
    std::memmove(data_.get() + at + s.size(), data_.get() + at, size_ - at);
    std::memcpy(data_.get() + at, s.data(), s.size());
    size_ += s.size();
  }

 private:
  void grow(std::size_t n) {
    std::size_t cap = cap_ < 256 ? 256 : cap_;
    while (cap - size_ < n) cap *= 2;
    reallocate(cap);
  }
  void reallocate(std::size_t cap) {
    auto bigger = std::make_unique_for_overwrite<char[]>(cap);
    if (size_) std::memcpy(bigger.get(), data_.get(), size_);
    data_ = std::move(bigger);
    cap_ = cap;
  }
  std::unique_ptr<char[]> data_;
  std::size_t size_ = 0, cap_ = 0;
};

}  // namespace twinpost
