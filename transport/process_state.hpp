#pragma once
/// @file
/// The states a process reports in STATUS (status_t.state). The message
/// carries the name, so stock LCM tools show it; a STATUS with any other
/// name is rejected (transport::validate).
///
///   ready -> running -> finished      (the run reached its last tick)
///                    -> interrupted   (stopped before it: a signal, a dead peer)
///                    -> failed        (it stopped the run, the message says why: a
///                                      program from outside -- an external plant's
///                                      limit or stall; the built-in processes exit
///                                      with an error instead)

#include "util/enum_names.hpp"

namespace lagrange::transport {

enum class ProcessState { kReady, kRunning, kFinished, kInterrupted, kFailed };

inline constexpr util::EnumName<ProcessState> kProcessStateNames[] = {
    {ProcessState::kReady, "ready"},
    {ProcessState::kRunning, "running"},
    {ProcessState::kFinished, "finished"},
    {ProcessState::kInterrupted, "interrupted"},
    {ProcessState::kFailed, "failed"}};

inline const char* toString(ProcessState state) { return util::nameOf(kProcessStateNames, state); }

}  // namespace lagrange::transport
