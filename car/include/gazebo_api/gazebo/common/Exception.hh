// car's Gazebo 11 API (docs/PLUGINS.md): gazebo::common::Exception and gzthrow, as Gazebo 11's common/Exception.hh
// has them: the exception prints itself on gzerr when made, and is not a std::exception. car's loader reports one
// thrown by Load or Init with its text (docs/COMPAT-plugins.md "Users' own plug-ins").
#pragma once

#include <cstdint>
#include <ostream>
#include <sstream>
#include <string>

#include "gazebo/common/Console.hh"

namespace gazebo {
namespace common {

class Exception {
 public:
  Exception() = default;
  Exception(const char* _file, int64_t _line, std::string _msg) : file(_file), line(_line), str(std::move(_msg)) {
    Print();
  }
  virtual ~Exception() = default;
  std::string GetErrorFile() const { return file + ":" + std::to_string(line); }
  std::string GetErrorStr() const { return str; }
  void Print() const { std::cerr << "[Err] [" << file << ":" << line << "] Exception: " << str << "\n"; }
  friend std::ostream& operator<<(std::ostream& _out, const Exception& _err) { return _out << _err.GetErrorStr(); }

 private:
  std::string file;
  int64_t line = 0;
  std::string str;
};

}  // namespace common
}  // namespace gazebo

// Throws a gazebo::common::Exception with the streamed message and the position.
#define gzthrow(msg)                                                              \
  {                                                                               \
    std::ostringstream throwStream;                                               \
    throwStream << msg << std::endl << std::flush;                                \
    throw gazebo::common::Exception(__FILE__, __LINE__, throwStream.str());       \
  }
