// Common to every stage. Errors as values: the core never throws past its boundary. Every public
// function returns a Status (or a result carrying one); the Python binding
// turns a failed Status into an exception naming the file, body and face.
#pragma once

#include <string>

namespace contactcore {

enum class StatusCode {
  Ok = 0,
  InvalidInput,    // empty shape, unreadable BRep string, bad argument
  ReadError,       // a file could not be opened or parsed
  GeometryError,   // OCCT raised Standard_Failure on a body or face
  Cancelled,       // the caller's progress callback asked to stop
  InvalidArgument, // an option out of range (a tolerance that is NaN, negative, too large)
  OutOfMemory,     // std::bad_alloc or OCCT's Standard_OutOfMemory (out_of_memory.h)
  Internal,        // a C++ exception that is neither OCCT's nor out of memory: a bug
};

struct Status {
  StatusCode code = StatusCode::Ok;
  std::string message;
  std::string file;  // file involved, if any
  std::string body;  // body name involved, if any
  int face = 0;      // 1-based face index (FreeCAD "FaceN"), 0 when none

  bool ok() const { return code == StatusCode::Ok; }
  static Status success() { return {}; }
  static Status failure(StatusCode c, std::string msg) {
    Status s;
    s.code = c;
    s.message = std::move(msg);
    return s;
  }
  // "message (file 'x', body 'y', Face3)"
  std::string describe() const;
};

const char* to_string(StatusCode code);

// Progress report and cancellation: called with a stage name and a fraction
// in [0, 1]; returning false cancels the work (the result then carries
// StatusCode::Cancelled).
struct Progress {
  virtual ~Progress() = default;
  virtual bool report(const char* stage, double fraction) = 0;
};

}  // namespace contactcore
