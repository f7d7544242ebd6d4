// car's Gazebo 11 API (docs/PLUGINS.md): gzmsg, gzwarn, gzerr, gzdbg, gzlog as streams (stdout for messages,
// stderr for warnings and errors, with Gazebo's "[Wrn]" / "[Err]" and the source position).
#pragma once

#include <iostream>

#define gzmsg (std::cout)
#define gzdbg (std::cout << "[Dbg] [" << __FILE__ << ":" << __LINE__ << "] ")
#define gzwarn (std::cerr << "[Wrn] [" << __FILE__ << ":" << __LINE__ << "] ")
#define gzerr (std::cerr << "[Err] [" << __FILE__ << ":" << __LINE__ << "] ")
#define gzlog (std::clog)
