// warning.cpp - the warning sink.
#include "core/warning.h"

#include <cstdio>
#include <mutex>

namespace ff {

namespace {
std::mutex& sinkMutex() {
  static std::mutex m;
  return m;
}
WarningSink& sink() {
  static WarningSink s;
  return s;
}
}  // namespace

void warn(const std::string& message) {
  std::lock_guard<std::mutex> lock(sinkMutex());
  if (sink())
    sink()(message);
  else
    std::fprintf(stderr, "flowform: warning: %s\n", message.c_str());
}

WarningSink setWarningSink(WarningSink s) {
  std::lock_guard<std::mutex> lock(sinkMutex());
  WarningSink old = std::move(sink());
  sink() = std::move(s);
  return old;
}

}  // namespace ff
