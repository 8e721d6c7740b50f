// SPDX-License-Identifier: GPL-3.0-or-later
// HOT PATH: HidOutputWriter::Post and HidOutputWriter::CommandDelayS run on the servo tick
// (wait-free: atomics and a Mailbox, no allocation, no lock, no system call). The rest
// runs on the writer thread or a control thread.
#include "hapticad/devices/hid/hid_output_writer.h"

#include <hidapi/hidapi.h>
#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cwchar>
#include <deque>
#include <mutex>
#include <thread>
#include <utility>

#include "hapticad/devices/mailbox.h"

namespace hapticad {
namespace {

// Posts stop being expected soon when none came for this long after the predicted time
// (the loop stopped or runs slowly): the thread then looks every kIdlePollS.
constexpr double kOverdueS = 5e-3;
constexpr double kOutsidePollS = 0.05;
constexpr int kIntervals = 4;  // the period is the shortest of the last four post gaps
constexpr int kReasonLength = 160;
constexpr int kEintrRetries = 3;
// the longest a bounded wait goes on for a thread that is not inside hidapi (not stuck,
// only not scheduled): a machine that starves it longer is past helping
constexpr double kStarvedS = 2.0;

void Bump(std::atomic<std::uint64_t>& counter, std::uint64_t n = 1) {
  counter.store(counter.load(std::memory_order_relaxed) + n, std::memory_order_relaxed);
}

std::chrono::steady_clock::time_point ToTimePoint(double monotonic_s) {
  // steady_clock is CLOCK_MONOTONIC on Linux (libstdc++)
  return std::chrono::steady_clock::time_point(
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(monotonic_s)));
}

// When the next post is due, from the times of the posts taken (the thread's own).
class PostClock {
 public:
  void Begin(double session_begin_s) {
    last_post_s_ = session_begin_s;
    count_ = 0;
    next_ = 0;
    seen_any_ = false;
  }
  void Observe(double post_s) {
    if (seen_any_ && post_s > last_post_s_) {
      intervals_[next_] = post_s - last_post_s_;
      next_ = (next_ + 1) % kIntervals;
      count_ = std::min(count_ + 1, kIntervals);
    }
    seen_any_ = true;
    last_post_s_ = std::max(last_post_s_, post_s);
  }
  // The monotonic time to look for a post next, at `now_s`: kLeadS before the next post
  // is due, then every kPollS; every kIdlePollS once it is kOverdueS late.
  double NextCheck(double now_s) const {
    double due = last_post_s_;  // before any post: from the session's start
    if (count_ > 0) {
      double period = intervals_[0];
      for (int i = 1; i < count_; ++i) period = std::min(period, intervals_[i]);
      due += period;
    }
    if (now_s < due - HidOutputWriter::kLeadS) {
      return std::min(due - HidOutputWriter::kLeadS, now_s + HidOutputWriter::kIdlePollS);
    }
    if (now_s < due + kOverdueS) return now_s + HidOutputWriter::kPollS;
    return now_s + HidOutputWriter::kIdlePollS;
  }

 private:
  double last_post_s_ = 0.0;
  double intervals_[kIntervals] = {};
  int count_ = 0;  // intervals held (at most kIntervals)
  int next_ = 0;   // where the next one goes
  bool seen_any_ = false;
};

}  // namespace

struct HidOutputWriter::State {
  explicit State(hid_device* h) : handle(h) {}
  State(const State&) = delete;
  State& operator=(const State&) = delete;

  hid_device* const handle;  // the thread's once it runs; it closes it before `exited`

  struct Slot {
    Report report{};
    std::uint64_t number = 0;    // 1, 2, ... per post
    double posted_real_s = 0.0;  // monotonic clock at the post
  };
  Mailbox<Slot> slot;
  std::atomic<std::uint64_t> posted{0};   // the tick: number of the newest report posted
  std::atomic<std::uint64_t> written{0};  // the thread: newest report written or dropped

  // the thread's results
  int failures_in_a_row = 0;  // the thread's
  std::uint64_t taken = 0;    // the thread's: number of the newest report taken
  wchar_t reason[kReasonLength] = {};
  std::atomic<bool> failed{false};  // written once, after `reason`
  std::atomic<std::uint64_t> writes{0}, writes_failed{0}, superseded{0}, interrupted{0}, wakeups{0};
  std::atomic<double> write_max_s{0.0}, write_last_s{0.0};
  std::atomic<double> busy_since_s{-1.0};
  std::atomic<int> policy{-1}, priority{0};

  // the posting thread, to copy its scheduling: written by the tick before servo_ready
  pthread_t servo_thread{};
  std::atomic<bool> servo_ready{false};

  // control, under the mutex
  std::mutex mutex;
  std::condition_variable wake;  // the thread waits on it
  std::condition_variable done;  // callers wait on it
  std::deque<std::function<void(hid_device*)>> jobs;
  std::uint64_t jobs_queued = 0;
  std::uint64_t jobs_done = 0;
  bool session = false;
  double session_begin_s = 0.0;
  bool adopted = false;  // the posting thread's scheduling was copied this session
  bool quit = false;
  bool exited = false;
};

namespace {

using State = HidOutputWriter::State;

// Gives the calling thread the scheduling policy and priority of `thread`, which the
// caller knows is alive, and notes what it got. Errors leave the scheduling as it was.
void CopyScheduling(pthread_t thread, State& s) {
  int policy = SCHED_OTHER;
  sched_param param{};
  if (pthread_getschedparam(thread, &policy, &param) == 0) {
    pthread_setschedparam(pthread_self(), policy, &param);
  }
  if (pthread_getschedparam(pthread_self(), &policy, &param) == 0) {
    s.priority.store(param.sched_priority, std::memory_order_relaxed);
    s.policy.store(policy, std::memory_order_relaxed);
  }
}

// The thread's: the reports posted and not yet taken are dropped (a job comes after them).
void DropPending(State& s) {
  if (!s.slot.has_news()) return;
  const State::Slot& slot = s.slot.Read();
  Bump(s.superseded, slot.number - s.taken);
  s.taken = slot.number;
  s.written.store(slot.number, std::memory_order_release);
}

void WriteNewest(State& s, PostClock* clock) {
  const State::Slot slot = s.slot.Read();  // a copy: 36 bytes
  if (slot.number > s.taken + 1) Bump(s.superseded, slot.number - s.taken - 1);
  s.taken = slot.number;
  clock->Observe(slot.posted_real_s);
  const double start = HidOutputWriter::MonotonicSeconds();
  s.busy_since_s.store(start, std::memory_order_relaxed);
  int n = -1;
  int error = 0;
  for (int attempt = 0; attempt <= kEintrRetries; ++attempt) {
    errno = 0;
    n = hid_write(s.handle, slot.report.data(), slot.report.size());
    error = errno;
    if (n >= 0 || error != EINTR) break;
    Bump(s.interrupted);  // a signal: not the device's fault; again, unless a newer one waits
    if (s.slot.has_news()) break;
  }
  const double took = HidOutputWriter::MonotonicSeconds() - start;
  s.busy_since_s.store(-1.0, std::memory_order_relaxed);
  Bump(s.writes);
  s.write_last_s.store(took, std::memory_order_relaxed);
  if (took > s.write_max_s.load(std::memory_order_relaxed)) {
    s.write_max_s.store(took, std::memory_order_relaxed);
  }
  if (n < 0 && error != EINTR) {
    Bump(s.writes_failed);
    if (++s.failures_in_a_row >= HidOutputWriter::kFailuresToGiveUp &&
        !s.failed.load(std::memory_order_relaxed)) {
      // hidapi's error text is this handle's, and only this thread uses the handle
      const wchar_t* text = hid_error(s.handle);
      std::wcsncpy(s.reason, text ? text : L"", kReasonLength - 1);
      s.reason[kReasonLength - 1] = L'\0';
      s.failed.store(true, std::memory_order_release);
    }
  } else if (n >= 0) {
    s.failures_in_a_row = 0;
  }
  s.written.store(slot.number, std::memory_order_release);
}

void Loop(std::shared_ptr<State> s) {
  // a sleeping normal thread wakes up to 50 us late by default; ask for 1 us (as the loop)
  prctl(PR_SET_TIMERSLACK, 1000UL, 0, 0, 0);
  pthread_setname_np(pthread_self(), "hid-writer");  // for top -H, perf, gdb
  PostClock clock;
  bool in_session = false;
  std::unique_lock<std::mutex> lock(s->mutex);
  while (true) {
    if (!s->jobs.empty()) {
      std::function<void(hid_device*)> job = std::move(s->jobs.front());
      s->jobs.pop_front();
      lock.unlock();
      DropPending(*s);
      s->busy_since_s.store(HidOutputWriter::MonotonicSeconds(), std::memory_order_relaxed);
      job(s->handle);
      s->busy_since_s.store(-1.0, std::memory_order_relaxed);
      job = nullptr;  // what it holds goes here, off the lock
      lock.lock();
      ++s->jobs_done;
      s->done.notify_all();
      continue;
    }
    if (s->session != in_session) {
      in_session = s->session;
      if (in_session) clock.Begin(s->session_begin_s);
    }
    if (s->slot.has_news()) {
      // the posting thread is alive until it calls EndSession(), which takes the lock
      if (s->session && !s->adopted && s->servo_ready.load(std::memory_order_acquire)) {
        CopyScheduling(s->servo_thread, *s);
        s->adopted = true;
      }
      lock.unlock();
      WriteNewest(*s, &clock);
      lock.lock();
      s->done.notify_all();
      continue;
    }
    if (s->quit) break;
    Bump(s->wakeups);
    if (s->session) {
      s->wake.wait_until(lock, ToTimePoint(clock.NextCheck(HidOutputWriter::MonotonicSeconds())));
    } else {
      // nothing is expected outside a session (callers wake the thread); a report posted
      // then anyway still goes out within kOutsidePollS
      s->wake.wait_for(lock, std::chrono::duration<double>(kOutsidePollS));
    }
  }
  // closed before `exited`: a destructor that saw the thread end returns with the handle
  // closed (closed after, by the last owner of the state, it raced the caller's next look)
  lock.unlock();
  hid_close(s->handle);
  lock.lock();
  s->exited = true;
  s->done.notify_all();
}

// Waits on `s.done` (the lock held) until `ready()`: true; false once at least `wait_s`
// has passed and the thread has been inside one hidapi call for `wait_s` (stuck in the
// kernel), or kStarvedS have passed. A thread not yet scheduled (a loaded machine) is not
// stuck: giving up on it after `wait_s` of the caller's clock called a working device one
// that does not take commands, and left its handle open after the destructor.
template <class Ready>
bool WaitUnlessStuck(State& s, std::unique_lock<std::mutex>& lock, double wait_s, Ready ready) {
  const double start = HidOutputWriter::MonotonicSeconds();
  const double give_up = start + std::max(wait_s, kStarvedS);
  while (!ready()) {
    const double now = HidOutputWriter::MonotonicSeconds();
    const double busy_since = s.busy_since_s.load(std::memory_order_relaxed);
    const double stuck_at = busy_since < 0.0 ? now + wait_s : busy_since + wait_s;
    if (now >= give_up || (now >= start + wait_s && busy_since >= 0.0 && now >= stuck_at)) {
      return false;
    }
    const double until = std::min(give_up, std::max(start + wait_s, stuck_at));
    s.done.wait_for(lock, std::chrono::duration<double>(until - now));
  }
  return true;
}

}  // namespace

double HidOutputWriter::MonotonicSeconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);  // vDSO: no system call
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

HidOutputWriter::HidOutputWriter(hid_device* handle) : state_(std::make_shared<State>(handle)) {
  std::thread(Loop, state_).detach();  // "joined" by waiting for `exited` (the destructor)
}

HidOutputWriter::~HidOutputWriter() {
  std::unique_lock<std::mutex> lock(state_->mutex);
  state_->quit = true;
  state_->session = false;
  state_->wake.notify_all();
  // the thread runs the jobs still queued first; one stuck in the kernel is left to
  // finish on its own, with the state it shares (it closes the handle when done)
  WaitUnlessStuck(*state_, lock, kAbandonAfterS, [&] { return state_->exited; });
}

void HidOutputWriter::Post(const Report& report, double now_s) {
  State& s = *state_;
  if (!thread_published_) {
    s.servo_thread = pthread_self();
    s.servo_ready.store(true, std::memory_order_release);
    thread_published_ = true;
  }
  State::Slot slot;
  slot.report = report;
  slot.number = ++posted_;
  slot.posted_real_s = MonotonicSeconds();
  s.slot.Write(slot);
  s.posted.store(posted_, std::memory_order_release);
  if (waiting_since_s_ < 0.0) waiting_since_s_ = now_s;
}

double HidOutputWriter::CommandDelayS(double now_s) {
  const std::uint64_t written = state_->written.load(std::memory_order_acquire);
  if (written >= posted_) {
    written_seen_ = written;
    waiting_since_s_ = -1.0;
    return 0.0;
  }
  if (written != written_seen_) {  // a write finished: the next one's wait starts now
    written_seen_ = written;
    waiting_since_s_ = now_s;
  }
  return waiting_since_s_ < 0.0 ? 0.0 : std::max(0.0, now_s - waiting_since_s_);
}

bool HidOutputWriter::failed() const { return state_->failed.load(std::memory_order_acquire); }

const wchar_t* HidOutputWriter::failure_reason() const { return failed() ? state_->reason : L""; }

HidWriterStats HidOutputWriter::Stats() const {
  const State& s = *state_;
  HidWriterStats out;
  out.posted = s.posted.load(std::memory_order_relaxed);
  out.writes = s.writes.load(std::memory_order_relaxed);
  out.writes_failed = s.writes_failed.load(std::memory_order_relaxed);
  out.superseded = s.superseded.load(std::memory_order_relaxed);
  out.interrupted = s.interrupted.load(std::memory_order_relaxed);
  out.wakeups = s.wakeups.load(std::memory_order_relaxed);
  out.write_max_s = s.write_max_s.load(std::memory_order_relaxed);
  out.write_last_s = s.write_last_s.load(std::memory_order_relaxed);
  out.policy = s.policy.load(std::memory_order_relaxed);
  out.priority = s.priority.load(std::memory_order_relaxed);
  return out;
}

double HidOutputWriter::busy_s() const {
  const double since = state_->busy_since_s.load(std::memory_order_relaxed);
  return since < 0.0 ? 0.0 : std::max(0.0, MonotonicSeconds() - since);
}

void HidOutputWriter::BeginSession() {
  std::lock_guard<std::mutex> lock(state_->mutex);
  state_->session = true;
  state_->session_begin_s = MonotonicSeconds();
  state_->adopted = false;
  state_->servo_ready.store(false, std::memory_order_relaxed);
  thread_published_ = false;  // no tick runs now (Device::BeginSession's contract)
  waiting_since_s_ = -1.0;
  state_->wake.notify_all();
}

void HidOutputWriter::EndSession() {
  std::lock_guard<std::mutex> lock(state_->mutex);
  state_->session = false;
  state_->adopted = false;
  state_->servo_ready.store(false, std::memory_order_relaxed);
}

bool HidOutputWriter::Run(std::function<void(hid_device*)> job, double wait_s) {
  std::unique_lock<std::mutex> lock(state_->mutex);
  state_->jobs.push_back(std::move(job));
  const std::uint64_t ticket = ++state_->jobs_queued;
  state_->wake.notify_all();
  return WaitUnlessStuck(*state_, lock, wait_s, [&] { return state_->jobs_done >= ticket; });
}

bool HidOutputWriter::WaitUntilWritten(double wait_s) {
  const std::uint64_t target = state_->posted.load(std::memory_order_acquire);
  std::unique_lock<std::mutex> lock(state_->mutex);
  state_->wake.notify_all();
  return WaitUnlessStuck(*state_, lock, wait_s,
                         [&] { return state_->written.load(std::memory_order_acquire) >= target; });
}

}  // namespace hapticad
