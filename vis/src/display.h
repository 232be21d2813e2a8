// An X display for VTK. Debian's VTK 9 is built for X11 only: creating a render window without a
// display it can open makes VTK abort (or crash inside GLX), so zenith-plot secures one first:
//   1. $DISPLAY, if XOpenDisplay accepts it;
//   2. otherwise a private Xvfb started here (`Xvfb -displayfd`), stopped when the guard dies;
//   3. otherwise a DisplayError that says what to install or set.
// libX11 is opened with dlopen, so this check works even where libX11 itself is missing.
#pragma once

#include <sys/types.h>

#include <stdexcept>
#include <string>

#include "zenith/base/error.h"

namespace zenith::vis {

class DisplayError : public Error {
  public:
    using Error::Error;
};

// Whether XOpenDisplay(name) succeeds (nullptr: $DISPLAY). Never aborts: a missing libX11 is
// reported as false with `why` filled in.
bool CanOpenDisplay(const char* name, std::string* why = nullptr);

// Owns the Xvfb it started, if any; restores the previous $DISPLAY on destruction.
class DisplayGuard {
  public:
    DisplayGuard() = default;
    ~DisplayGuard();
    DisplayGuard(const DisplayGuard&) = delete;
    DisplayGuard& operator=(const DisplayGuard&) = delete;
    DisplayGuard(DisplayGuard&& other) noexcept;
    DisplayGuard& operator=(DisplayGuard&&) = delete;

    const std::string& display() const { return display_; }
    bool started_xvfb() const { return xvfb_pid_ > 0; }

  private:
    friend DisplayGuard EnsureDisplay(bool verbose);
    std::string display_;
    pid_t xvfb_pid_ = -1;
    bool had_display_ = false;
    std::string previous_display_;
};

// Makes $DISPLAY name a display that opens (see above); throws DisplayError otherwise. With
// verbose, says on stderr when it starts Xvfb.
DisplayGuard EnsureDisplay(bool verbose = false);

}  // namespace zenith::vis
