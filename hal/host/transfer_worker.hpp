// The asynchronous half of a host PanelBus: one thread that performs a pixel transfer (a
// sequence of pieces: spidev ioctls, USB bulk transfers) while the caller renders, and a wait
// bounded by a timeout.
//
// A job is `pieces` calls of TransferSteps::piece(0..pieces-1) in order, then one call of
// finish(). The worker stops after the first failed piece. When wait() times out the job is
// abandoned: wait() returns kTimeout at once, the worker completes the piece it is in (an ioctl
// or a USB transfer cannot be interrupted), skips the remaining pieces, still runs finish() (the
// FT232H bus releases chip select there, so the wire is left in a known state) and the result is
// discarded. Until that piece is over the bus cannot start anything else: idle() waits for it,
// bounded too.
//
// Host-side only (std::thread, std::mutex): used by hal/host/linux/spidev_bus and
// hal/host/usb/ft232h_bus. Header-only and free of libgpiod and libusb, so both libraries (and the
// tests) can use it.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "lineraster/core/output/status.hpp"

namespace lr::backend {

// What a job does; implemented by the bus. Called on the worker thread.
class TransferSteps {
 public:
  // One piece of the transfer; false when it failed (the job ends, finish() still runs).
  virtual bool piece(size_t index) = 0;
  // After the last piece, after a failed piece and after an abandon; false when it failed.
  virtual bool finish() = 0;

 protected:
  TransferSteps() = default;
  ~TransferSteps() = default;
};

class TransferWorker {
 public:
  // Starts the thread; nullptr and a one-line error when the system refused one.
  static std::unique_ptr<TransferWorker> create(TransferSteps& steps, std::string& error) {
    std::unique_ptr<TransferWorker> w(new (std::nothrow) TransferWorker(steps));
    if (!w) {
      error = "out of memory for the transfer thread";
      return nullptr;
    }
    try {
      w->thread_ = std::thread([p = w.get()] { p->run(); });
    } catch (const std::exception& e) {
      error = std::string("cannot start the transfer thread (") + e.what() + ")";
      return nullptr;
    }
    return w;
  }

  TransferWorker(const TransferWorker&) = delete;
  TransferWorker& operator=(const TransferWorker&) = delete;

  // Abandons a job in flight (its current piece completes) and joins the thread.
  ~TransferWorker() {
    {
      std::lock_guard<std::mutex> lock(m_);
      quit_ = true;
      abandon_ = true;
    }
    cv_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

  // May the bus use the wire? kOk when no job is in flight, after waiting up to timeout_ms for
  // an abandoned one to finish its piece; kBusy when a started job has not been waited for
  // (the caller must wait() first); kTimeout when the abandoned job is still running.
  Status idle(uint32_t timeout_ms) {
    std::unique_lock<std::mutex> lock(m_);
    if (pending_) return Status::kBusy;
    if (!cv_.wait_for(lock, std::chrono::milliseconds(timeout_ms), [this] { return !busy_; })) {
      return Status::kTimeout;
    }
    return Status::kOk;
  }

  // Starts a job of `pieces` pieces. Call only after idle() returned kOk (the bus prepares the
  // job's data in between, while nothing reads it); kBusy otherwise.
  Status start(size_t pieces) {
    {
      std::lock_guard<std::mutex> lock(m_);
      if (pending_ || busy_) return Status::kBusy;
      pieces_ = pieces;
      abandon_ = false;
      ok_ = true;
      queued_ = true;
      busy_ = true;
      pending_ = true;
    }
    cv_.notify_all();
    return Status::kOk;
  }

  // Waits at most timeout_ms for the job started last: kOk (at once when none is pending),
  // kDisplayError when a piece or finish() failed, kTimeout when it did not end in time (the
  // job is then abandoned and its result discarded).
  Status wait(uint32_t timeout_ms) {
    std::unique_lock<std::mutex> lock(m_);
    if (!pending_) return Status::kOk;
    pending_ = false;
    if (!cv_.wait_for(lock, std::chrono::milliseconds(timeout_ms), [this] { return !busy_; })) {
      abandon_ = true;
      return Status::kTimeout;
    }
    return ok_ ? Status::kOk : Status::kDisplayError;
  }

  // A job started and not yet waited for.
  bool pending() const {
    std::lock_guard<std::mutex> lock(m_);
    return pending_;
  }

 private:
  explicit TransferWorker(TransferSteps& steps) : steps_(steps) {}

  void run() {
    std::unique_lock<std::mutex> lock(m_);
    for (;;) {
      cv_.wait(lock, [this] { return queued_ || quit_; });
      if (!queued_) return;  // quit with nothing queued
      queued_ = false;
      const size_t pieces = pieces_;
      bool ok = true;
      for (size_t i = 0; i < pieces && ok && !abandon_; ++i) {
        lock.unlock();
        ok = steps_.piece(i);
        lock.lock();
      }
      lock.unlock();
      const bool finished = steps_.finish();
      lock.lock();
      ok_ = ok && finished;
      busy_ = false;
      cv_.notify_all();
    }
  }

  TransferSteps& steps_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  size_t pieces_ = 0;
  bool queued_ = false;   // a job waits for the thread to pick it up
  bool busy_ = false;     // a job is queued or running (until finish() returned)
  bool pending_ = false;  // started and not yet collected by wait()
  bool abandon_ = false;  // stop before the next piece
  bool ok_ = true;        // result of the last job
  bool quit_ = false;
  std::thread thread_;
};

}  // namespace lr::backend
