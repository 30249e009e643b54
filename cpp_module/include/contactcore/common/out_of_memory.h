// Common to every stage. Out of memory is never a skipped face, pair or body: the handlers that
// turn an OCCT or C++ failure into a note let it through, and the stage's
// outermost handler ends the call with StatusCode::OutOfMemory (the Python
// binding raises MemoryError; the CLI exits 4 naming the file).
#pragma once

#include <new>

#include <Standard_OutOfMemory.hxx>

// Put before a `catch (const Standard_Failure&)` or `catch (const
// std::exception&)` that records the failure and goes on:
//   try { ... } CONTACTS_PASS_OUT_OF_MEMORY catch (const Standard_Failure& f) { ... }
#define CONTACTS_PASS_OUT_OF_MEMORY         \
  catch (const std::bad_alloc&) { throw; }  \
  catch (const Standard_OutOfMemory&) { throw; }
