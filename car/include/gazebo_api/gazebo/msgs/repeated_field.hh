// car's Gazebo 11 API: the part of protobuf's RepeatedField<T> that Gazebo plug-ins use on a message's repeated
// numbers (laserscan.pb.h's ranges, ...): begin/end, size, Get, operator[], Add, Resize, Clear, data. car's messages
// are plain classes, not protobuf (vector3d.pb.h).
#pragma once

#include <vector>

namespace gazebo {
namespace msgs {

template <typename T>
class RepeatedField {
 public:
  using const_iterator = typename std::vector<T>::const_iterator;
  using iterator = typename std::vector<T>::iterator;
  const_iterator begin() const { return v_.begin(); }
  const_iterator end() const { return v_.end(); }
  iterator begin() { return v_.begin(); }
  iterator end() { return v_.end(); }
  int size() const { return static_cast<int>(v_.size()); }
  bool empty() const { return v_.empty(); }
  const T& Get(int _i) const { return v_.at(_i); }
  void Set(int _i, const T& _v) { v_.at(_i) = _v; }
  const T& operator[](int _i) const { return v_[_i]; }
  T& operator[](int _i) { return v_[_i]; }
  void Add(const T& _v) { v_.push_back(_v); }
  void Resize(int _n, const T& _v) { v_.resize(_n, _v); }
  void Reserve(int _n) { v_.reserve(_n); }
  void Clear() { v_.clear(); }
  const T* data() const { return v_.data(); }
  T* mutable_data() { return v_.data(); }

 private:
  std::vector<T> v_;
};

}  // namespace msgs
}  // namespace gazebo
