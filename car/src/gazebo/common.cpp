// car's Gazebo 11 API: common::Time, common::PID and event::Connection (docs/PLUGINS.md). car's own code; the
// rules are Gazebo 11's as its documentation and sources state them.
#include <time.h>

#include <cmath>
#include <cstdio>
#include <utility>

#include "gazebo/common/Console.hh"
#include "gazebo/common/Event.hh"
#include "gazebo/common/Image.hh"
#include "gazebo/common/PID.hh"
#include "gazebo/common/Plugin.hh"
#include "gazebo/common/Time.hh"

namespace gazebo {
namespace common {

const Time Time::Zero(0, 0);
const int32_t Time::nsInSec = 1000000000;
const int32_t Time::nsInMs = 1000000;

namespace {

int64_t ns_of(const Time& t) { return static_cast<int64_t>(t.sec) * 1000000000 + t.nsec; }

Time of_ns(int64_t ns) {
  // sec and nsec of one sign, as Gazebo's Correct()
  return Time(static_cast<int32_t>(ns / 1000000000), static_cast<int32_t>(ns % 1000000000));
}

}  // namespace

Time::Time() : sec(0), nsec(0) {}
Time::Time(const Time& _time) : sec(_time.sec), nsec(_time.nsec) {}
Time::Time(int32_t _sec, int32_t _nsec) : sec(_sec), nsec(_nsec) { this->Correct(); }
Time::Time(double _time) : sec(0), nsec(0) { this->Set(_time); }
Time::~Time() = default;

void Time::Set(int32_t _sec, int32_t _nsec) {
  this->sec = _sec;
  this->nsec = _nsec;
  this->Correct();
}

// floor for the seconds, the rest rounded to the nanosecond
void Time::Set(double _seconds) {
  this->sec = static_cast<int32_t>(std::floor(_seconds));
  this->nsec = static_cast<int32_t>(std::round((_seconds - this->sec) * 1e9));
  this->Correct();
}

double Time::Double() const { return static_cast<double>(this->sec) + static_cast<double>(this->nsec) * 1e-9; }
float Time::Float() const { return static_cast<float>(this->Double()); }

Time& Time::operator=(const Time& _time) {
  this->sec = _time.sec;
  this->nsec = _time.nsec;
  return *this;
}
Time Time::operator+(const Time& _time) const { return of_ns(ns_of(*this) + ns_of(_time)); }
const Time& Time::operator+=(const Time& _time) { return *this = *this + _time; }
Time Time::operator-(const Time& _time) const { return of_ns(ns_of(*this) - ns_of(_time)); }
const Time& Time::operator-=(const Time& _time) { return *this = *this - _time; }
Time Time::operator*(const Time& _time) const { return Time(this->Double() * _time.Double()); }
const Time& Time::operator*=(const Time& _time) { return *this = *this * _time; }
Time Time::operator/(const Time& _time) const { return Time(this->Double() / _time.Double()); }
const Time& Time::operator/=(const Time& _time) { return *this = *this / _time; }
bool Time::operator==(const Time& _time) const { return ns_of(*this) == ns_of(_time); }
bool Time::operator==(double _time) const { return *this == Time(_time); }
bool Time::operator!=(const Time& _time) const { return !(*this == _time); }
bool Time::operator!=(double _time) const { return !(*this == _time); }
bool Time::operator<(const Time& _time) const { return ns_of(*this) < ns_of(_time); }
bool Time::operator<(double _time) const { return *this < Time(_time); }
bool Time::operator<=(const Time& _time) const { return ns_of(*this) <= ns_of(_time); }
bool Time::operator<=(double _time) const { return *this <= Time(_time); }
bool Time::operator>(const Time& _time) const { return ns_of(*this) > ns_of(_time); }
bool Time::operator>(double _time) const { return *this > Time(_time); }
bool Time::operator>=(const Time& _time) const { return ns_of(*this) >= ns_of(_time); }
bool Time::operator>=(double _time) const { return *this >= Time(_time); }

void Time::Correct() {
  const int64_t ns = ns_of(*this);
  this->sec = static_cast<int32_t>(ns / 1000000000);
  this->nsec = static_cast<int32_t>(ns % 1000000000);
}

PID::PID(double _p, double _i, double _d, double _imax, double _imin, double _cmdMax, double _cmdMin) {
  this->Init(_p, _i, _d, _imax, _imin, _cmdMax, _cmdMin);
}
PID::~PID() = default;

void PID::Init(double _p, double _i, double _d, double _imax, double _imin, double _cmdMax, double _cmdMin) {
  pGain = _p;
  iGain = _i;
  dGain = _d;
  iMax = _imax;
  iMin = _imin;
  cmdMax = _cmdMax;
  cmdMin = _cmdMin;
  this->Reset();
}

void PID::SetPGain(double _p) { pGain = _p; }
void PID::SetIGain(double _i) { iGain = _i; }
void PID::SetDGain(double _d) { dGain = _d; }
void PID::SetIMax(double _i) { iMax = _i; }
void PID::SetIMin(double _i) { iMin = _i; }
void PID::SetCmdMax(double _c) { cmdMax = _c; }
void PID::SetCmdMin(double _c) { cmdMin = _c; }
double PID::GetPGain() const { return pGain; }
double PID::GetIGain() const { return iGain; }
double PID::GetDGain() const { return dGain; }
double PID::GetIMax() const { return iMax; }
double PID::GetIMin() const { return iMin; }
double PID::GetCmdMax() const { return cmdMax; }
double PID::GetCmdMin() const { return cmdMin; }
void PID::SetCmd(double _cmd) { cmd = _cmd; }
double PID::GetCmd() { return cmd; }

void PID::GetErrors(double& _pe, double& _ie, double& _de) {
  _pe = pErr;
  _ie = iErr;
  _de = dErr;
}

void PID::Reset() {
  pErrLast = pErr = iErr = dErr = cmd = 0.0;
}

double PID::Update(double _error, common::Time _dt) {
  pErr = _error;
  if (_dt == Time::Zero || !std::isfinite(_error)) return 0.0;
  const double dt = _dt.Double();
  iErr += dt * pErr;
  double i = iGain * iErr;
  // the integral term within [iMin, iMax], its error with it
  if (i > iMax) {
    i = iMax;
    iErr = i / iGain;
  } else if (i < iMin) {
    i = iMin;
    iErr = i / iGain;
  }
  dErr = (pErr - pErrLast) / dt;
  pErrLast = pErr;
  cmd = -(pGain * pErr) - i - dGain * dErr;
  if (cmdMax >= cmdMin) cmd = std::min(std::max(cmd, cmdMin), cmdMax);
  return cmd;
}

// ---- Time: the wall clock and sleeping, as Gazebo 11's common/Time.cc -------------------------------------------

const Time& Time::GetWallTime() {
  static thread_local Time wall;
  struct timespec tv;
  clock_gettime(CLOCK_REALTIME, &tv);
  wall = Time(static_cast<int32_t>(tv.tv_sec), static_cast<int32_t>(tv.tv_nsec));
  return wall;
}

const std::string& Time::GetWallTimeAsISOString() {
  static thread_local std::string iso;
  struct timespec tv;
  clock_gettime(CLOCK_REALTIME, &tv);
  struct tm local;
  localtime_r(&tv.tv_sec, &local);
  char text[64];
  const size_t n = strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%S", &local);
  snprintf(text + n, sizeof(text) - n, ".%06ld", static_cast<long>(tv.tv_nsec / 1000));
  iso = text;
  return iso;
}

void Time::SetToWallTime() { *this = GetWallTime(); }

// A time below the clock's resolution (1 ns here; zero and negative times) sleeps not at all and says so on gzlog,
// with upstream's words.
Time Time::Sleep(const common::Time& _time) {
  Time left;
  struct timespec resolution;
  clock_getres(CLOCK_REALTIME, &resolution);
  if (!(_time >= Time(static_cast<int32_t>(resolution.tv_sec), static_cast<int32_t>(resolution.tv_nsec)))) {
    gzlog << "Sleep time is larger than clock resolution, skipping sleep\n";
    return left;
  }
  struct timespec interval, remainder;
  interval.tv_sec = _time.sec;
  interval.tv_nsec = _time.nsec;
  if (clock_nanosleep(CLOCK_MONOTONIC, 0, &interval, &remainder) != 0) {
    left.sec = static_cast<int32_t>(remainder.tv_sec);
    left.nsec = static_cast<int32_t>(remainder.tv_nsec);
  }
  return left;
}

Time Time::MSleep(unsigned int _ms) { return Sleep(Time(0, static_cast<int32_t>(_ms * 1000000))); }

Time Time::NSleep(unsigned int _ns) { return Sleep(Time(0, static_cast<int32_t>(_ns))); }

// As Gazebo 11's Image::ConvertPixelFormat (common/Image.cc): the older names first, then PixelFormatNames.
Image::PixelFormat Image::ConvertPixelFormat(const std::string& _format) {
  if (_format == "L8" || _format == "L_INT8") return L_INT8;
  if (_format == "L16" || _format == "L_INT16" || _format == "L_UINT16") return L_INT16;
  if (_format == "R8G8B8" || _format == "RGB_INT8") return RGB_INT8;
  if (_format == "R16G16B16" || _format == "RGB_INT16" || _format == "RGB_UINT16") return RGB_INT16;
  if (_format == "FLOAT32") return R_FLOAT32;
  if (_format == "FLOAT16") return R_FLOAT16;
  for (unsigned int i = 0; i < PIXEL_FORMAT_COUNT; ++i)
    if (PixelFormatNames[i] == _format) return static_cast<PixelFormat>(i);
  return UNKNOWN_PIXEL_FORMAT;
}

}  // namespace common

namespace event {

namespace {
int g_next_connection = 0;
}

Connection::Connection(std::function<void()> _disconnect) : disconnect(std::move(_disconnect)), id(g_next_connection++) {}
Connection::~Connection() {
  if (disconnect) disconnect();
}
int Connection::Id() const { return id; }

}  // namespace event
}  // namespace gazebo

namespace gazebo {

// out of line, so that a plug-in library needs car_gazebo (Plugin.hh)
PluginBase::~PluginBase() = default;

}  // namespace gazebo
