// SPDX-License-Identifier: GPL-3.0-or-later
// HidOutputWriter: the thread that hands a HID device its force commands, so that the
// servo tick never waits on USB. On Linux, hidraw's write() returns when the USB transfer
// is done: about a millisecond when the device takes it, and up to 5 s (usbhid's
// USB_CTRL_SET_TIMEOUT, then ETIMEDOUT) when the device stops taking output reports. The
// tick posts the newest output report into a wait-free single slot (Mailbox) and goes
// on; this thread writes it with hid_write(). A report not yet taken when a newer one is
// posted is replaced (counted as superseded): only the newest command matters.
//
// The thread has a hidapi handle of its own on the device and is the only user of it:
// hidapi 0.13's per-handle error text is freed and replaced by every call without a lock,
// so a read on the servo thread and a write here on one handle could free it twice.
// hidraw accepts several opens of one device; output and feature reports sent on either
// reach the same device (each handle also gets its own copy of the input reports, which
// this thread never reads: the kernel keeps 64 and drops the rest).
//
// How the tick learns that commands do not get through: CommandDelayS() says how long a
// posted command has waited without the thread finishing a write; failed() turns true
// after three failed writes in a row (hidapi's words kept in failure_reason()). HidDevice
// turns these into a device fault and, past kCommandTimeoutS, a lost device.
//
// Waking without a system call on the tick: during a session the thread does not sleep
// on a futex the tick would have to wake; it predicts the next post from the posts'
// times (the tick's period) and wakes kLeadS before it, then every kPollS until the post
// is there (a few wakeups per tick, adding at most kPollS to the latency). The thread
// copies the scheduling policy and priority of the thread that posts (SCHED_FIFO when
// the servo loop got it), so it is not starved by a busy desktop.
//
// Threads. Post() and CommandDelayS(): the servo tick of the session in progress (one
// thread per session, which calls EndSession() before it exits); wait-free, no
// allocation, no lock, no system call. failed(), failure_reason(), Stats() and busy_s():
// any thread. BeginSession(), EndSession(), Run(), WaitUntilWritten(): a control thread,
// or the servo thread off the tick (they lock and may allocate). Their waits are bounded
// by the caller's wait_s as spent by the thread inside one hidapi call: a wait gives up
// once wait_s has passed and the thread has been inside one call for wait_s (stuck in the
// kernel), and waits on, at most 2 s in all, for a thread that is only not scheduled yet
// (a loaded machine), which is not the device's fault.
//
// Ending: the destructor waits for the thread so (kAbandonAfterS), which closes its
// handle before it ends: a destructor that did not abandon it returns with the handle
// closed (a device opened again at once is not still held). A thread still
// inside hidapi then (a write stuck in the kernel) is abandoned, detached: when the call
// returns it runs the jobs still queued (the session close), closes its handle and frees
// its state, touching nothing of its owner's. A process may exit meanwhile: the kernel
// ends the transfer. (hidapi 0.13.1's hid_close() touches no global state, so the
// detached thread's close is safe alongside other hidapi calls.)
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>

#include "hapticad/devices/hid/hid_protocol.h"

struct hid_device_;

namespace hapticad {

struct HidWriterStats {
  std::uint64_t posted = 0;         // reports the tick posted
  std::uint64_t writes = 0;         // hid_write() calls that returned
  std::uint64_t writes_failed = 0;  // of those, failed (interrupted ones are not counted)
  std::uint64_t superseded = 0;     // reports replaced by a newer one before being written
  std::uint64_t interrupted = 0;    // writes that returned EINTR (not failures)
  std::uint64_t wakeups = 0;        // times the thread woke (timed or woken) to look
  double write_max_s = 0.0;         // the longest a hid_write() took (s)
  double write_last_s = 0.0;        // how long the last one took (s)
  // the thread's scheduling as copied from the posting thread (sched.h policy; -1: not yet)
  int policy = -1;
  int priority = 0;
};

class HidOutputWriter {
 public:
  using Report = std::array<std::uint8_t, hid::kOutputReportSize>;

  static constexpr double kLeadS = 60e-6;        // wakes this long before a predicted post
  static constexpr double kPollS = 20e-6;        // then polls this often until it is there
  static constexpr double kIdlePollS = 1e-3;     // in a session with no post for a while
  static constexpr int kFailuresToGiveUp = 3;    // failed writes in a row: the device is gone
  static constexpr double kAbandonAfterS = 0.1;  // the destructor's wait bound (above)

  // Takes `handle` (opened for this writer alone; closed when the thread ends) and starts
  // the thread. Throws std::system_error if no thread can be started (or std::bad_alloc);
  // the caller then still owns `handle`.
  explicit HidOutputWriter(hid_device_* handle);
  ~HidOutputWriter();
  HidOutputWriter(const HidOutputWriter&) = delete;
  HidOutputWriter& operator=(const HidOutputWriter&) = delete;

  // ---- the servo tick: wait-free, no allocation, no lock, no system call
  // Hands `report` to the thread, replacing one not yet taken. `now_s`: the caller's
  // clock, the one CommandDelayS() is asked with.
  void Post(const Report& report, double now_s);
  // How long (s, the caller's clock) the oldest command not yet written has waited
  // without the thread finishing a write; 0 when every posted report is written. Each
  // finished write restarts the wait (as seen at this call), so a device that takes
  // reports slower than they are posted shows a delay of about one write, not a growing one.
  double CommandDelayS(double now_s);

  // ---- any thread
  // True once kFailuresToGiveUp writes in a row failed (final). failure_reason() is then
  // hidapi's text for the last of them (UTF-32, taken on the writer thread).
  bool failed() const;
  const wchar_t* failure_reason() const;
  HidWriterStats Stats() const;
  // How long (s, monotonic clock) the thread has been inside hidapi, 0 when it is not.
  double busy_s() const;

  // ---- control thread, or the servo thread off the tick
  // A session begins: the thread polls for posts (above) until EndSession(). Also forgets
  // the posting thread, so the next session's thread is copied again.
  void BeginSession();
  // The session's posting thread is done (called on it, before it exits): the thread stops
  // polling and stops looking at it.
  void EndSession();
  // Runs `job` on the thread with its handle, after the write under way (reports posted
  // before it and not yet written are dropped: the job's own writes come after them).
  // Waits for it as bounded by `wait_s` (above); true if it finished. Otherwise it runs when the
  // thread gets to it (also after the destructor: it must own what it uses).
  bool Run(std::function<void(hid_device_*)> job, double wait_s);
  // Waits until every report posted so far is written (or failed), bounded by `wait_s`, and
  // wakes the thread at once for them. True if so. For callers that step the tick by hand
  // (tests, tools) and need the writes done before they go on; does not allocate.
  bool WaitUntilWritten(double wait_s);

  // The monotonic clock, s (CLOCK_MONOTONIC, through the vDSO: no system call).
  static double MonotonicSeconds();

  struct State;  // shared with the thread (defined in the .cc)

 private:
  std::shared_ptr<State> state_;
  // the tick's
  std::uint64_t posted_ = 0;
  std::uint64_t written_seen_ = 0;
  double waiting_since_s_ = -1.0;
  bool thread_published_ = false;
};

}  // namespace hapticad
