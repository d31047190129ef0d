// warning.h - messages about input that is used anyway (an open mesh, ...).
// They go to stderr as "flowform: warning: ..." unless a sink is set (tests,
// the viewer's panel).
#pragma once
#include <functional>
#include <string>

namespace ff {

using WarningSink = std::function<void(const std::string&)>;

// Reports `message` (it names the file and the problem).
void warn(const std::string& message);
// Replaces where warnings go; an empty sink restores stderr. Returns the old one.
WarningSink setWarningSink(WarningSink sink);

}  // namespace ff
