#include "swemps/io/gdal_messages.hpp"

#include <cpl_error.h>
#include <gdal.h>

#include <mutex>
#include <utility>

namespace swemps::io {

namespace {

std::mutex sink_mutex;
GdalMessageSink& current_sink() {
  static GdalMessageSink sink;
  return sink;
}

void CPL_STDCALL forward(CPLErr level, CPLErrorNum /*number*/, const char* message) {
  const std::lock_guard lock(sink_mutex);
  if (current_sink()) current_sink()(level >= CE_Failure, message ? message : "");
}

}  // namespace

void send_gdal_messages_to(GdalMessageSink sink) {
  const std::lock_guard lock(sink_mutex);
  current_sink() = std::move(sink);
  CPLSetErrorHandler(current_sink() ? forward : CPLDefaultErrorHandler);
}

QuietGdalErrors::QuietGdalErrors() {
  CPLPushErrorHandler(CPLQuietErrorHandler);
  CPLErrorReset();
}

QuietGdalErrors::~QuietGdalErrors() { CPLPopErrorHandler(); }

void register_gdal_drivers() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

std::string gdal_detail() {
  const char* message = CPLGetLastErrorMsg();
  return message && *message ? std::string(" (GDAL: ") + message + ")" : std::string();
}

}  // namespace swemps::io
