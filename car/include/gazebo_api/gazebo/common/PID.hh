// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::common::PID, Gazebo's PID rule (command = -(p e + i sum e dt +
// d de/dt), the integral term clamped to [imin, imax], the command to [cmdMin, cmdMax] when cmdMax >= cmdMin).
#pragma once

#include "gazebo/common/Time.hh"

namespace gazebo {
namespace common {

class PID {
 public:
  PID(double _p = 0.0, double _i = 0.0, double _d = 0.0, double _imax = 0.0, double _imin = 0.0,
      double _cmdMax = -1.0, double _cmdMin = 0.0);
  virtual ~PID();
  void Init(double _p = 0.0, double _i = 0.0, double _d = 0.0, double _imax = 0.0, double _imin = 0.0,
            double _cmdMax = -1.0, double _cmdMin = 0.0);
  void SetPGain(double _p);
  void SetIGain(double _i);
  void SetDGain(double _d);
  void SetIMax(double _i);
  void SetIMin(double _i);
  void SetCmdMax(double _c);
  void SetCmdMin(double _c);
  double GetPGain() const;
  double GetIGain() const;
  double GetDGain() const;
  double GetIMax() const;
  double GetIMin() const;
  double GetCmdMax() const;
  double GetCmdMin() const;
  // _error = state - target; returns the command. A zero _dt or a non-finite error returns 0.
  double Update(double _error, common::Time _dt);
  void SetCmd(double _cmd);
  double GetCmd();
  void GetErrors(double& _pe, double& _ie, double& _de);
  PID& operator=(const PID& _p) = default;
  void Reset();

 private:
  double pErrLast = 0.0, pErr = 0.0, iErr = 0.0, dErr = 0.0;
  double pGain, iGain, dGain, iMax, iMin, cmd = 0.0, cmdMax, cmdMin;
};

}  // namespace common
}  // namespace gazebo
