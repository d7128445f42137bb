// The worker behind the host buses' asynchronous pixel transfers: pieces in order, failures,
// the bounded wait, abandoning on timeout (the piece in flight completes, the rest is skipped,
// finish() still runs, the bus is usable again) and the calls that are refused meanwhile.
#include "lineraster/hal/host/transfer_worker.hpp"

#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace lr::backend {
namespace {

// Records the pieces; piece `block_at` waits until release(); piece `fail_at` fails.
class FakeSteps final : public TransferSteps {
 public:
  bool piece(size_t index) override {
    std::unique_lock<std::mutex> lock(m_);
    pieces_.push_back(index);
    if (index == block_at_) {
      blocked_ = true;
      cv_.notify_all();
      cv_.wait(lock, [this] { return released_; });
    }
    return index != fail_at_;
  }
  bool finish() override {
    std::lock_guard<std::mutex> lock(m_);
    ++finishes_;
    return finish_ok_;
  }
  void release() {
    std::lock_guard<std::mutex> lock(m_);
    released_ = true;
    cv_.notify_all();
  }
  void wait_blocked() {
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait(lock, [this] { return blocked_; });
  }
  std::vector<size_t> pieces() {
    std::lock_guard<std::mutex> lock(m_);
    return pieces_;
  }
  int finishes() {
    std::lock_guard<std::mutex> lock(m_);
    return finishes_;
  }

  size_t block_at_ = SIZE_MAX;
  size_t fail_at_ = SIZE_MAX;
  bool finish_ok_ = true;

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<size_t> pieces_;
  int finishes_ = 0;
  bool blocked_ = false;
  bool released_ = false;
};

std::unique_ptr<TransferWorker> make(FakeSteps& steps) {
  std::string err;
  auto w = TransferWorker::create(steps, err);
  EXPECT_TRUE(w) << err;
  return w;
}

TEST(TransferWorker, NothingPendingIsOkAtOnce) {
  FakeSteps steps;
  auto w = make(steps);
  EXPECT_EQ(w->wait(0), Status::kOk);
  EXPECT_EQ(w->idle(0), Status::kOk);
  EXPECT_FALSE(w->pending());
}

TEST(TransferWorker, RunsThePiecesInOrderThenFinish) {
  FakeSteps steps;
  auto w = make(steps);
  ASSERT_EQ(w->idle(0), Status::kOk);
  ASSERT_EQ(w->start(3), Status::kOk);
  EXPECT_TRUE(w->pending());
  EXPECT_EQ(w->wait(5000), Status::kOk);
  EXPECT_EQ(steps.pieces(), (std::vector<size_t>{0, 1, 2}));
  EXPECT_EQ(steps.finishes(), 1);
  EXPECT_EQ(w->wait(0), Status::kOk);  // collected: nothing pending
}

TEST(TransferWorker, AFailedPieceEndsTheJobWithDisplayError) {
  FakeSteps steps;
  steps.fail_at_ = 1;
  auto w = make(steps);
  ASSERT_EQ(w->start(4), Status::kOk);
  EXPECT_EQ(w->wait(5000), Status::kDisplayError);
  EXPECT_EQ(steps.pieces(), (std::vector<size_t>{0, 1}));
  EXPECT_EQ(steps.finishes(), 1);
  // Usable again.
  steps.fail_at_ = SIZE_MAX;
  ASSERT_EQ(w->idle(0), Status::kOk);
  ASSERT_EQ(w->start(1), Status::kOk);
  EXPECT_EQ(w->wait(5000), Status::kOk);
}

TEST(TransferWorker, AFailedFinishIsADisplayError) {
  FakeSteps steps;
  steps.finish_ok_ = false;
  auto w = make(steps);
  ASSERT_EQ(w->start(2), Status::kOk);
  EXPECT_EQ(w->wait(5000), Status::kDisplayError);
}

TEST(TransferWorker, ASecondStartBeforeWaitIsRefused) {
  FakeSteps steps;
  steps.block_at_ = 0;
  auto w = make(steps);
  ASSERT_EQ(w->start(1), Status::kOk);
  EXPECT_EQ(w->start(1), Status::kBusy);
  EXPECT_EQ(w->idle(0), Status::kBusy);  // the bus must wait() first
  steps.release();
  EXPECT_EQ(w->wait(5000), Status::kOk);
  EXPECT_EQ(w->idle(0), Status::kOk);
}

TEST(TransferWorker, TimeoutAbandonsTheRestAndTheBusStaysUsable) {
  FakeSteps steps;
  steps.block_at_ = 0;
  auto w = make(steps);
  ASSERT_EQ(w->start(3), Status::kOk);
  steps.wait_blocked();
  EXPECT_EQ(w->wait(20), Status::kTimeout);
  EXPECT_FALSE(w->pending());
  // The piece in flight cannot be interrupted: the bus is not idle until it completes.
  EXPECT_EQ(w->idle(10), Status::kTimeout);
  EXPECT_EQ(w->start(1), Status::kBusy);
  steps.release();
  EXPECT_EQ(w->idle(5000), Status::kOk);
  EXPECT_EQ(steps.pieces(), (std::vector<size_t>{0}));  // pieces 1 and 2 skipped
  EXPECT_EQ(steps.finishes(), 1);                       // finish() still ran
  EXPECT_EQ(w->wait(0), Status::kOk);                   // the result was discarded
  // A new job runs normally.
  ASSERT_EQ(w->start(2), Status::kOk);
  EXPECT_EQ(w->wait(5000), Status::kOk);
  EXPECT_EQ(steps.pieces(), (std::vector<size_t>{0, 0, 1}));
  EXPECT_EQ(steps.finishes(), 2);
}

TEST(TransferWorker, DestructionWaitsForThePieceInFlight) {
  FakeSteps steps;
  steps.block_at_ = 0;
  {
    auto w = make(steps);
    ASSERT_EQ(w->start(5), Status::kOk);
    steps.wait_blocked();
    std::thread releaser([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      steps.release();
    });
    w.reset();  // joins after the blocked piece, skipping the others
    releaser.join();
  }
  EXPECT_EQ(steps.pieces(), (std::vector<size_t>{0}));
  EXPECT_EQ(steps.finishes(), 1);
}

}  // namespace
}  // namespace lr::backend
