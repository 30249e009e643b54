#include "contactcore/common/errors.h"

namespace contactcore {

const char* to_string(StatusCode code) {
  switch (code) {
    case StatusCode::Ok: return "ok";
    case StatusCode::InvalidInput: return "invalid input";
    case StatusCode::ReadError: return "read error";
    case StatusCode::GeometryError: return "geometry error";
    case StatusCode::Cancelled: return "cancelled";
    case StatusCode::InvalidArgument: return "invalid argument";
    case StatusCode::OutOfMemory: return "out of memory";
    case StatusCode::Internal: return "internal error";
  }
  return "unknown";
}

std::string Status::describe() const {
  std::string out = message.empty() ? to_string(code) : message;
  std::string where;
  auto add = [&where](const std::string& part) {
    where += where.empty() ? "" : ", ";
    where += part;
  };
  if (!file.empty()) add("file '" + file + "'");
  if (!body.empty()) add("body '" + body + "'");
  if (face > 0) add("Face" + std::to_string(face));
  if (!where.empty()) out += " (" + where + ")";
  return out;
}

}  // namespace contactcore
