#include "contactcore/common/occt_guard.h"

#include <csignal>
#include <mutex>
#include <system_error>
#include <vector>

#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <OSD.hxx>
#include <Standard_OutOfMemory.hxx>

namespace contactcore {

namespace {

// Keeps warnings and failures instead of printing them.
class CapturingPrinter : public Message_Printer {
 public:
  std::vector<std::string> lines;

 protected:
  void send(const TCollection_AsciiString& text, const Message_Gravity gravity) const override {
    if (gravity < Message_Warning) return;
    // Worker threads of a guarded stage may send at once.
    std::lock_guard<std::mutex> lock(mutex_);
    if (lines.size() >= kMaxLines) return;
    std::string line = text.ToCString();
    // OCCT colours its console output: drop the escape sequences.
    std::string clean;
    for (size_t i = 0; i < line.size(); ++i) {
      if (line[i] == '\x1b') {
        while (i < line.size() && line[i] != 'm') ++i;
        continue;
      }
      clean += line[i];
    }
    const_cast<CapturingPrinter*>(this)->lines.push_back(clean);
  }

 private:
  static constexpr size_t kMaxLines = 200;
  mutable std::mutex mutex_;
};

std::recursive_mutex& guard_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

// The classic signals OCCT's handler takes over (1..31).
constexpr int kLastClassicSignal = 31;

// Room for OCCT's handler (a message, an exception object, the jump) when the
// thread's own stack is exhausted.
constexpr size_t kSignalStackBytes = 256 * 1024;

}  // namespace

struct OcctGuard::State {
  std::unique_lock<std::recursive_mutex> lock{guard_mutex()};
  struct sigaction saved[kLastClassicSignal + 1];
  Handle(Message_Messenger) messenger = Message::DefaultMessenger();
  Message_SequenceOfPrinters printers;
  Handle(CapturingPrinter) capture = new CapturingPrinter;
  std::vector<char> signal_stack;  // ours, when the thread had none
  stack_t saved_signal_stack{};
};

OcctGuard::OcctGuard() : state_(std::make_unique<State>()) {
  for (int s = 1; s <= kLastClassicSignal; ++s) sigaction(s, nullptr, &state_->saved[s]);
  OSD::SetSignal(OSD_SignalMode_Set, false);
  // OCCT's handler for SIGINT would turn Ctrl-C into an exception at a random
  // point of the reader: keep the caller's.
  sigaction(SIGINT, &state_->saved[SIGINT], nullptr);
  // A stack overflow (OCCT recursing along a chain of references the checks
  // did not bound) is a SIGSEGV whose handler cannot run on the exhausted
  // stack: the kernel would kill the process. On a stack of its own it
  // becomes a Standard_Failure like any other.
  sigaltstack(nullptr, &state_->saved_signal_stack);
  if (state_->saved_signal_stack.ss_flags & SS_DISABLE) {
    state_->signal_stack.resize(kSignalStackBytes);
    stack_t ours{};
    ours.ss_sp = state_->signal_stack.data();
    ours.ss_size = state_->signal_stack.size();
    if (sigaltstack(&ours, nullptr) != 0) state_->signal_stack.clear();
  }
  for (int s : {SIGSEGV, SIGBUS}) {
    struct sigaction action;
    sigaction(s, nullptr, &action);
    action.sa_flags |= SA_ONSTACK;
    sigaction(s, &action, nullptr);
  }
  state_->printers = state_->messenger->Printers();
  state_->messenger->ChangePrinters().Clear();
  state_->messenger->AddPrinter(state_->capture);
}

OcctGuard::~OcctGuard() {
  state_->messenger->ChangePrinters().Clear();
  for (const Handle(Message_Printer)& printer : state_->printers) state_->messenger->AddPrinter(printer);
  for (int s = 1; s <= kLastClassicSignal; ++s) {
    if (s == SIGKILL || s == SIGSTOP) continue;
    sigaction(s, &state_->saved[s], nullptr);
  }
  if (!state_->signal_stack.empty()) sigaltstack(&state_->saved_signal_stack, nullptr);
}

std::vector<std::string> OcctGuard::messages() const { return state_->capture->lines; }

Status status_of_current_exception() {
  try {
    throw;
  } catch (const Standard_OutOfMemory&) {
    return Status::failure(StatusCode::OutOfMemory, "out of memory");
  } catch (const Standard_Failure& failure) {
    // Some OCCT exceptions carry no message: name their type then.
    const char* text = failure.GetMessageString();
    return Status::failure(StatusCode::GeometryError, std::string("OCCT ") + failure.DynamicType()->Name() +
                                                          (text && *text ? std::string(": ") + text : ""));
  } catch (const std::bad_alloc&) {
    return Status::failure(StatusCode::OutOfMemory, "out of memory");
  } catch (const std::system_error& error) {
    // A thread or a mapping the system could not give: memory, not a bug.
    if (error.code() == std::errc::not_enough_memory || error.code() == std::errc::resource_unavailable_try_again)
      return Status::failure(StatusCode::OutOfMemory, std::string("out of memory (") + error.what() + ")");
    return Status::failure(StatusCode::Internal, error.what());
  } catch (const std::exception& error) {
    return Status::failure(StatusCode::Internal, *error.what() ? error.what() : "C++ exception without a message");
  } catch (...) {
    return Status::failure(StatusCode::Internal, "an exception that is not a C++ std::exception");
  }
}

std::string occt_failure_text(const Standard_Failure& failure) {
  const char* text = failure.GetMessageString();
  return text && *text ? std::string(text) : std::string(failure.DynamicType()->Name());
}

}  // namespace contactcore
