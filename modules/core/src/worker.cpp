#include "stereoscout/core/worker.hpp"

#include "stereoscout/core/check.hpp"

namespace stereoscout::core {

Worker::Worker() : thread_([this] { run(); }) {}

Worker::~Worker() {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    job_done_.wait(lock, [this] { return !busy_; });
    stopping_ = true;
  }
  job_ready_.notify_one();
  thread_.join();
}

void Worker::start(Job job, void* context) {
  STEREOSCOUT_CHECK(job != nullptr, "Worker::start without a job");
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    STEREOSCOUT_CHECK(!busy_, "Worker::start while the job before is still running");
    job_ = job;
    context_ = context;
    busy_ = true;
  }
  job_ready_.notify_one();
}

void Worker::wait() {
  std::unique_lock<std::mutex> lock(mutex_);
  job_done_.wait(lock, [this] { return !busy_; });
}

bool Worker::busy() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return busy_;
}

void Worker::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    job_ready_.wait(lock, [this] { return stopping_ || job_ != nullptr; });
    if (job_ == nullptr) return;  // stopping, and nothing left to run
    const Job job = job_;
    void* const context = context_;
    job_ = nullptr;
    lock.unlock();
    job(context);
    lock.lock();
    busy_ = false;
    job_done_.notify_all();
  }
}

}  // namespace stereoscout::core
