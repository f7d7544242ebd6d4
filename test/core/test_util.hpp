// Helpers shared by the core tests.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

inline std::string read_text(const std::string& rel) {
  std::ifstream in(std::string(CAR_SOURCE_DIR) + "/" + rel);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::string data_path(const std::string& rel) { return std::string(CAR_SOURCE_DIR) + "/test/data/" + rel; }
