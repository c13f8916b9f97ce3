#pragma once
// Where GDAL's own messages go. Left alone, GDAL prints every error and warning to stderr as
// "ERROR 1: ...", which breaks the rule that a failure is one line saying what to change.
// The readers and writers hold GDAL quiet while they call it and fold its complaints into
// their exceptions; whatever GDAL reports outside them goes to the sink set here.

#include <functional>
#include <string>
#include <string_view>

namespace swemps::io {

// Receives each message GDAL reports outside a QuietGdalErrors scope, from any thread:
// `is_error` for failures, false for warnings and notes. Replaces the sink before it.
using GdalMessageSink = std::function<void(bool is_error, std::string_view message)>;
void send_gdal_messages_to(GdalMessageSink sink);

// While alive, GDAL keeps its messages to itself on this thread; the last one stays readable
// with CPLGetLastErrorMsg(), cleared when the scope starts.
class QuietGdalErrors {
 public:
  QuietGdalErrors();
  ~QuietGdalErrors();
  QuietGdalErrors(const QuietGdalErrors&) = delete;
  QuietGdalErrors& operator=(const QuietGdalErrors&) = delete;
};

// GDAL's drivers, registered once for the process, before the first file is opened.
void register_gdal_drivers();

// " (GDAL: <the last message>)", for an exception's text; empty when GDAL said nothing.
std::string gdal_detail();

}  // namespace swemps::io
