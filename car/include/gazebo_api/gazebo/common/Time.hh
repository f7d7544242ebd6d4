// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::common::Time, sim time in whole seconds and nanoseconds.
// Declarations follow Gazebo 11's names and signatures; the implementation is car's (src/gazebo/common.cpp).
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

namespace gazebo {
namespace common {

class Time {
 public:
  Time();
  Time(const Time& _time);
  Time(int32_t _sec, int32_t _nsec);
  Time(double _time);  // NOLINT: implicit, as upstream
  virtual ~Time();

  void Set(int32_t _sec, int32_t _nsec);
  void Set(double _seconds);
  double Double() const;
  float Float() const;

  Time& operator=(const Time& _time);
  Time operator+(const Time& _time) const;
  const Time& operator+=(const Time& _time);
  Time operator-(const Time& _time) const;
  const Time& operator-=(const Time& _time);
  Time operator*(const Time& _time) const;
  const Time& operator*=(const Time& _time);
  Time operator/(const Time& _time) const;
  const Time& operator/=(const Time& _time);
  bool operator==(const Time& _time) const;
  bool operator==(double _time) const;
  bool operator!=(const Time& _time) const;
  bool operator!=(double _time) const;
  bool operator<(const Time& _time) const;
  bool operator<(double _time) const;
  bool operator<=(const Time& _time) const;
  bool operator<=(double _time) const;
  bool operator>(const Time& _time) const;
  bool operator>(double _time) const;
  bool operator>=(const Time& _time) const;
  bool operator>=(double _time) const;

  friend std::ostream& operator<<(std::ostream& _out, const Time& _time) {
    _out << _time.sec << " " << _time.nsec;
    return _out;
  }

  // The wall clock (CLOCK_REALTIME), as Gazebo 11's; a plug-in that reads it is not deterministic, in car as there.
  static const Time& GetWallTime();
  // Local wall time as "YYYY-MM-DDTHH:MM:SS.ffffff" (boost's to_iso_extended_string, as Gazebo 11's).
  static const std::string& GetWallTimeAsISOString();
  void SetToWallTime();
  // Sleeps the calling thread for _time (CLOCK_MONOTONIC); returns what was left if interrupted, else zero. A time
  // below the clock's resolution (zero, negative) does not sleep and logs "Sleep time is larger than clock
  // resolution, skipping sleep" on gzlog, as Gazebo 11's.
  static Time Sleep(const common::Time& _time);
  static Time MSleep(unsigned int _ms);
  static Time NSleep(unsigned int _ns);

  static const Time Zero;
  static const int32_t nsInSec;
  static const int32_t nsInMs;

  int32_t sec;
  int32_t nsec;

 private:
  void Correct();
};

}  // namespace common
}  // namespace gazebo
