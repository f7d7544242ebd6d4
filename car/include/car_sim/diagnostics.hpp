// Load errors and diagnostics of the car_sim core. No ROS headers.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace car_sim {

enum class Severity { Info, Warning, Error };

const char* to_string(Severity s);

// One finding about an input file: where it is and why it matters.
struct Diagnostic {
  Severity severity = Severity::Warning;
  std::string code;     // stable key, e.g. "axis-normalised", "colour-range"
  std::string element;  // element path, e.g. "link[camera]/visual/material[no]/color"
  std::string message;  // human-readable reason
  int line = 0;         // line in the source document, 0 when unknown
};

// Thrown when an input cannot be loaded. what() reads "FILE[:LINE]: ELEMENT: REASON".
class LoadError : public std::runtime_error {
 public:
  LoadError(std::string file, int line, std::string element, std::string reason);

  const std::string& file() const { return file_; }
  int line() const { return line_; }  // 0 when unknown
  const std::string& element() const { return element_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_;
  int line_;
  std::string element_;
  std::string reason_;
};

// A plug-in that does not load while its model does (ResolveContext::drop): a LoadError where the plug-in is
// resolved alone, a warning where its model is.
class PluginNotLoaded : public LoadError {
 public:
  using LoadError::LoadError;
};

// Thrown by World::step when a body's state turned non-finite (a blow-up): what() names the body, the value and
// the sim time; the world stays stopped there (every later step throws too) until it is reset or the model removed.
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace car_sim
