#pragma once
// Fast ASCII output for the grid files (private): integers and doubles
// through std::to_chars (doubles in their shortest form that reads back
// exactly), appended to one buffer written in one go.
#include <charconv>
#include <string>
#include <string_view>

namespace meshgen {

class TextOut {
 public:
  explicit TextOut(std::size_t reserve = 0) { buf_.reserve(reserve); }
  TextOut& operator<<(std::string_view s) {
    buf_.append(s);
    return *this;
  }
  TextOut& operator<<(char c) {
    buf_.push_back(c);
    return *this;
  }
  TextOut& operator<<(long v) { return put(v); }
  TextOut& operator<<(int v) { return put(v); }
  TextOut& operator<<(std::size_t v) { return put(v); }
  TextOut& operator<<(double v) { return put(v); }
  const std::string& str() const { return buf_; }

 private:
  template <class T>
  TextOut& put(T v) {
    char tmp[32];
    const auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
    buf_.append(tmp, r.ptr);
    return *this;
  }
  std::string buf_;
};

}  // namespace meshgen
